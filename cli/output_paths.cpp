#include "output_paths.h"

#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <map>

#include "commands.h"
#include "util/atomic_file.h"

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
  // The write itself is tried (its temporary file created and removed, the name's length
  // checked), so a name the folder cannot hold fails now, not after the render.
  if (const std::string problem = atomic_write_problem(path); !problem.empty())
    throw BadArgument(std::string(option) + " " + path + ": " + problem);
}

namespace {

// The file's identity when it exists (device, inode); the lexical absolute path otherwise.
std::string file_identity(const std::string& path) {
  struct stat status {};
  if (::stat(path.c_str(), &status) == 0)
    return fmt::format("inode {}:{}", static_cast<uint64_t>(status.st_dev),
                       static_cast<uint64_t>(status.st_ino));
  // Made absolute first: weakly_canonical leaves "out.png" relative (no part of it exists) but
  // resolves "./out.png" (the two were not seen to be one file).
  std::error_code error;
  const std::filesystem::path absolute =
      std::filesystem::weakly_canonical(std::filesystem::absolute(path, error), error);
  return "path " + (error ? std::filesystem::path(path).lexically_normal().string() : absolute.string());
}

}  // namespace

void refuse_outputs_over_inputs(const std::vector<OutputFile>& outputs,
                                const std::vector<std::string>& inputs) {
  std::map<std::string, std::string> input_of;  // identity → the input's path
  for (const std::string& input : inputs)
    if (!input.empty()) input_of.emplace(file_identity(input), input);
  std::map<std::string, const OutputFile*> output_of;
  for (const OutputFile& output : outputs) {
    const std::string identity = file_identity(output.path);
    if (const auto found = input_of.find(identity); found != input_of.end())
      throw BadArgument(fmt::format("{} {}: that is {}, an input of this run (it would be overwritten)",
                                    output.option, output.path, found->second));
    const auto [place, added] = output_of.emplace(identity, &output);
    if (!added && (place->second->option != output.option || place->second->path != output.path))
      throw BadArgument(fmt::format("{} {}: the same file as {} {} (one would overwrite the other)",
                                    output.option, output.path, place->second->option, place->second->path));
  }
}

}  // namespace candela::cli
