#include "util/atomic_file.h"

#include <unistd.h>

#include <filesystem>
#include <stdexcept>

namespace candela {

void write_atomically(const std::string& path, const std::function<void(const std::string&)>& write) {
  namespace fs = std::filesystem;
  const fs::path target(path);
  // Keep the extension last: some writers choose the format by it.
  const fs::path temporary = target.parent_path() /
      (".tmp-" + std::to_string(::getpid()) + "-" + target.filename().string());
  try {
    write(temporary.string());
    fs::rename(temporary, target);
  } catch (...) {
    std::error_code ignored;
    fs::remove(temporary, ignored);
    throw;
  }
}

}  // namespace candela
