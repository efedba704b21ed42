// Checks every sub-command makes on its output paths before any work (SPEC §15: fail before the
// work, not after it).
#pragma once

#include <string>
#include <vector>

namespace candela::cli {

// The file's folder must exist and accept new files (outputs are renamed into place there), the
// path must not be a folder, and the file's name and its temporary's must fit the folder (tried:
// util/atomic_file.h's atomic_write_problem). Throws BadArgument naming the option.
void check_writable(const std::string& path, const char* option);

// One file a run will write, and the option that names it.
struct OutputFile {
  std::string path;
  std::string option;  // "-o", "--stats", …
};

// No data loss: throws BadArgument before any work when an output is one of the run's
// inputs (the same file, by device and inode, however the paths are spelled: the scene, a mesh, a
// texture, a luminaire, the relight file, the checkpoint resumed from — render leaves that out when
// --checkpoint names it: a run goes on writing the checkpoint it resumed), or when two outputs of the
// run are the same file (the same option naming the same path twice is one output).
void refuse_outputs_over_inputs(const std::vector<OutputFile>& outputs,
                                const std::vector<std::string>& inputs);

}  // namespace candela::cli
