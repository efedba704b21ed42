// Reading an input file whole, safely: only a regular file is
// opened — a FIFO would block in open() forever, a device such as /dev/zero would be read until
// memory ran out, a directory reads as nothing — and only up to a size limit known before the
// content is read. Every refusal is an InputError naming the path and what is wrong with it.
#pragma once

#include <cstdint>
#include <string>

namespace candela {

// The largest input text read whole by default: 1 GiB (a scene, a light set-up, probe points).
inline constexpr uint64_t kDefaultInputLimit = uint64_t{1} << 30;
// The largest binary input read whole: 4 GiB (an image, a mesh, a glTF buffer, a checkpoint).
inline constexpr uint64_t kLargeInputLimit = uint64_t{1} << 32;

// What is wrong with `path` as an input file of the given kind ("the scene file"), or "" when it is
// a readable regular file of at most `limit` bytes: it does not exist, is a directory, a FIFO, a
// device or a socket, or is larger than the limit.
std::string input_file_problem(const std::string& path, const std::string& what,
                               uint64_t limit = kDefaultInputLimit);

// The whole file; throws InputError({path, 0, 0, {}}, "...") for every problem above, for a read
// error, and when the file grows past the limit while it is read (at most limit + 1 bytes are read).
std::string read_input_file(const std::string& path, const std::string& what,
                            uint64_t limit = kDefaultInputLimit);

}  // namespace candela
