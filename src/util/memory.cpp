#include "util/memory.h"

#include <fstream>
#include <limits>
#include <string>

namespace candela {

uint64_t physical_memory_bytes() {
  std::ifstream meminfo("/proc/meminfo");
  std::string key, unit;
  uint64_t kibibytes = 0;
  while (meminfo >> key) {
    if (key == "MemTotal:") {
      if (meminfo >> kibibytes >> unit && unit == "kB") return kibibytes * 1024;
      return 0;
    }
    meminfo.ignore(std::numeric_limits<std::streamsize>::max(), '\n');
  }
  return 0;
}

}  // namespace candela
