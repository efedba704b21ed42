#include "output_paths.h"

#include <unistd.h>

#include <filesystem>

#include "commands.h"

namespace candela::cli {

void check_writable(const std::string& path, const char* option) {
  namespace fs = std::filesystem;
  const fs::path parent = fs::path(path).parent_path().empty() ? fs::path(".") : fs::path(path).parent_path();
  std::error_code error;
  if (!fs::is_directory(parent, error))
    throw BadArgument(std::string(option) + " " + path + ": the folder " + parent.string() +
                      " does not exist");
  if (::access(parent.c_str(), W_OK) != 0)
    throw BadArgument(std::string(option) + " " + path + ": the folder " + parent.string() +
                      " is not writable");
  if (fs::is_directory(path, error)) throw BadArgument(std::string(option) + " " + path + " is a folder");
}

}  // namespace candela::cli
