// Outputs are written to a temporary file beside the target and renamed into place, so a
// failure never leaves a half-written file (SPEC §15).
//
// The temporary's name always fits the file system's 255-byte limit, whatever the
// target's length: ".tmp-PID-HASH.EXT" (HASH: 16 hex digits of the target's file name, EXT: the
// target's extension when it is short, since some writers choose the format by it). A process
// killed while writing (SIGKILL, power loss) leaves its temporary behind; the next write of the same
// target removes the temporaries of that target whose process no longer runs.
#pragma once

#include <functional>
#include <string>
#include <string_view>

namespace candela {

// The temporary file this process writes `path` through.
std::string temporary_path_for(const std::string& path);

// Creates and removes the temporary file of `path` and checks that the target's own name is not
// longer than its folder allows, so that a write can fail before the work, not after it. Returns
// what is wrong ("" when the write can be made): e.g. "its name is longer than the folder allows
// (256 bytes, at most 255)".
std::string atomic_write_problem(const std::string& path);

// Calls write(temporary_path), then renames it to path. On any exception the temporary file
// is removed and the exception propagates. Stale temporaries of `path` left by processes that no
// longer run are removed first.
void write_atomically(const std::string& path, const std::function<void(const std::string&)>& write);

// Writes text (as bytes: no newline translation) to path atomically; std::runtime_error
// "cannot write PATH" when that fails (the old file, if any, stays).
void write_text_atomically(const std::string& path, std::string_view text);

}  // namespace candela
