// Outputs are written to a temporary file beside the target and renamed into place, so a
// failure never leaves a half-written file (SPEC §15).
#pragma once

#include <functional>
#include <string>
#include <string_view>

namespace candela {

// Calls write(temporary_path), then renames it to path. On any exception the temporary file
// is removed and the exception propagates.
void write_atomically(const std::string& path, const std::function<void(const std::string&)>& write);

// Writes text (as bytes: no newline translation) to path atomically; std::runtime_error
// "cannot write PATH" when that fails (the old file, if any, stays).
void write_text_atomically(const std::string& path, std::string_view text);

}  // namespace candela
