// Checks every sub-command makes on its output paths before any work (SPEC §15: fail before the
// work, not after it).
#pragma once

#include <string>

namespace candela::cli {

// The file's folder must exist and accept new files (outputs are renamed into place there), and
// the path must not be a folder. Throws BadArgument naming the option.
void check_writable(const std::string& path, const char* option);

}  // namespace candela::cli
