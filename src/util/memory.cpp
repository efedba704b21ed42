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

uint64_t memory_limit_bytes(double limit_mib) {
  if (!(limit_mib > 0)) {
    const uint64_t physical = physical_memory_bytes();
    return physical > 0 ? physical / 2 : uint64_t{8} << 30;
  }
  const double bytes = limit_mib * 1048576.0;
  // Saturated: beyond 2⁶⁴ bytes the conversion would be undefined.
  return bytes >= 18446744073709549568.0 ? std::numeric_limits<uint64_t>::max()
                                         : static_cast<uint64_t>(bytes);
}

}  // namespace candela
