#include "util/atomic_file.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "util/hash.h"

namespace candela {

namespace {

namespace fs = std::filesystem;

fs::path folder_of(const fs::path& target) {
  return target.parent_path().empty() ? fs::path(".") : target.parent_path();
}

// "HASH.EXT": what every temporary of this target ends with, whichever process wrote it. An
// extension longer than 16 bytes is left out (no writer chooses its format by such a one).
std::string temporary_suffix(const fs::path& target) {
  const std::string extension = target.extension().string();
  return fmt::format("{:016x}{}", fnv1a_64(target.filename().string()),
                     extension.size() <= 16 ? extension : std::string());
}

// Removes ".tmp-PID-SUFFIX" files of `target` whose process PID has ended (a run killed while it
// wrote). A live process's temporary is left alone: it may be writing now. Errors are ignored:
// cleaning is a courtesy, the write itself does not depend on it.
void remove_stale_temporaries(const fs::path& target) {
  const std::string suffix = temporary_suffix(target);
  std::error_code error;
  for (fs::directory_iterator entry(folder_of(target), error), end; !error && entry != end;
       entry.increment(error)) {
    const std::string name = entry->path().filename().string();
    if (name.rfind(".tmp-", 0) != 0 || name.size() <= 5 + suffix.size() + 1) continue;
    const std::size_t dash = name.find('-', 5);
    if (dash == std::string::npos || name.compare(dash + 1, std::string::npos, suffix) != 0) continue;
    const std::string digits = name.substr(5, dash - 5);
    if (digits.empty() || digits.size() > 9 || digits.find_first_not_of("0123456789") != std::string::npos)
      continue;
    const pid_t pid = static_cast<pid_t>(std::stol(digits));
    if (pid == ::getpid() || ::kill(pid, 0) == 0 || errno != ESRCH) continue;
    std::error_code ignored;
    fs::remove(entry->path(), ignored);
  }
}

}  // namespace

std::string temporary_path_for(const std::string& path) {
  const fs::path target(path);
  return (target.parent_path() / (".tmp-" + std::to_string(::getpid()) + "-" + temporary_suffix(target)))
      .string();
}

std::string atomic_write_problem(const std::string& path) {
  const fs::path target(path);
  const fs::path folder = folder_of(target);
  const std::size_t name_length = target.filename().string().size();
  errno = 0;
  const long name_max = ::pathconf(folder.c_str(), _PC_NAME_MAX);
  if (name_max > 0 && name_length > static_cast<std::size_t>(name_max))
    return fmt::format("its name is longer than the folder allows ({} bytes, at most {})", name_length,
                       name_max);
  const std::string temporary = temporary_path_for(path);
  const int descriptor = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_CLOEXEC, 0666);
  if (descriptor < 0)
    return fmt::format("cannot create a file in {} ({})", folder.string(), std::strerror(errno));
  ::close(descriptor);
  ::unlink(temporary.c_str());
  return {};
}

void write_atomically(const std::string& path, const std::function<void(const std::string&)>& write) {
  const fs::path target(path);
  remove_stale_temporaries(target);
  // The extension stays last (temporary_suffix): some writers choose the format by it.
  const fs::path temporary = temporary_path_for(path);
  try {
    write(temporary.string());
    fs::rename(temporary, target);
  } catch (...) {
    std::error_code ignored;
    fs::remove(temporary, ignored);
    throw;
  }
}

void write_text_atomically(const std::string& path, std::string_view text) {
  write_atomically(path, [&](const std::string& temporary) {
    std::ofstream out(temporary, std::ios::binary);
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
    out.close();
    if (!out) throw std::runtime_error("cannot write " + path);
  });
}

}  // namespace candela
