#include "util/input_file.h"

#include <fmt/format.h>
#include <sys/stat.h>

#include <cerrno>
#include <cstring>
#include <fstream>

#include "util/error.h"

namespace candela {

std::string input_file_problem(const std::string& path, const std::string& what, uint64_t limit) {
  struct stat status {};
  if (::stat(path.c_str(), &status) != 0)
    return fmt::format("cannot open {}: {}", what, std::strerror(errno));
  if (S_ISDIR(status.st_mode)) return fmt::format("{} is a directory, not a file", what);
  if (S_ISFIFO(status.st_mode)) return fmt::format("{} is a FIFO (named pipe), not a regular file", what);
  if (S_ISCHR(status.st_mode) || S_ISBLK(status.st_mode))
    return fmt::format("{} is a device, not a regular file", what);
  if (S_ISSOCK(status.st_mode)) return fmt::format("{} is a socket, not a regular file", what);
  if (!S_ISREG(status.st_mode)) return fmt::format("{} is not a regular file", what);
  if (static_cast<uint64_t>(status.st_size) > limit)
    return fmt::format("{} is {} bytes, more than the {} bytes read at most", what, status.st_size, limit);
  return "";
}

std::string read_input_file(const std::string& path, const std::string& what, uint64_t limit) {
  const std::string problem = input_file_problem(path, what, limit);
  if (!problem.empty()) throw InputError({path, 0, 0, {}}, problem);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError({path, 0, 0, {}}, fmt::format("cannot open {}", what));
  std::string text;
  char buffer[1 << 16];
  while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
    text.append(buffer, static_cast<std::size_t>(in.gcount()));
    // A file that grows while it is read (or lied about its size) is cut off at the limit.
    if (text.size() > limit)
      throw InputError({path, 0, 0, {}}, fmt::format("{} grew past the {} bytes read at most", what, limit));
  }
  if (in.bad()) throw InputError({path, 0, 0, {}}, fmt::format("cannot read {}", what));
  return text;
}

}  // namespace candela
