#include "io/checkpoint_file.h"

#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <type_traits>

#include "util/atomic_file.h"
#include "util/error.h"
#include "util/hash.h"

namespace candela {

namespace {

// The checksum runs over the bytes as characters.
std::string_view as_text(std::span<const std::byte> bytes) {
  return {reinterpret_cast<const char*>(bytes.data()), bytes.size()};
}

}  // namespace

// A color is its three doubles, r, g, b, with nothing between: an array of them is the count,
// then r, g, b of each.
static_assert(std::is_trivially_copyable_v<Color> && sizeof(Color) == 3 * sizeof(double));

void CheckpointWriter::put_colors(const std::vector<Color>& colors) {
  put_array(colors);
}

void CheckpointWriter::write(const std::string& path) const {
  std::string file(as_text(bytes()));
  const uint64_t checksum = fnv1a_64(file);
  file.append(reinterpret_cast<const char*>(&checksum), sizeof(checksum));
  write_atomically(path, [&](const std::string& temporary) {
    std::ofstream out(temporary, std::ios::binary);
    out.write(file.data(), static_cast<std::streamsize>(file.size()));
    out.close();
    if (!out) throw std::runtime_error("cannot write the checkpoint " + path);
  });
}

CheckpointReader::CheckpointReader(const std::string& path, std::string_view magic)
    : path_(path), reader_(bytes_, "checkpoint") {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail("cannot open the checkpoint");
  const std::string file{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (file.compare(0, magic.size(), magic) != 0)
    fail("not a " + std::string(magic.substr(0, magic.find_last_not_of(" \n") + 1)) + " checkpoint");
  if (file.size() < magic.size() + sizeof(uint64_t)) fail("the checkpoint is truncated");
  uint64_t checksum = 0;
  std::memcpy(&checksum, file.data() + file.size() - sizeof(checksum), sizeof(checksum));
  const std::string_view checked(file.data(), file.size() - sizeof(checksum));
  if (checksum != fnv1a_64(checked))
    fail("the checkpoint is corrupt (checksum mismatch: truncated or changed)");
  const std::string_view fields = checked.substr(magic.size());
  bytes_.resize(fields.size());
  if (!fields.empty()) std::memcpy(bytes_.data(), fields.data(), fields.size());
  reader_ = ByteReader(bytes_, "checkpoint");
}

std::string CheckpointReader::get_string() {
  try {
    return reader_.get_string();
  } catch (const ByteStreamError& e) {
    fail_read(e);
  }
}

std::vector<Color> CheckpointReader::get_colors() {
  try {
    return reader_.get_array<Color>();
  } catch (const ByteStreamError& e) {
    if (e.kind() == ByteStreamError::Kind::long_array) fail("the checkpoint is corrupt (color count)");
    fail_read(e);
  }
}

void CheckpointReader::finish() const {
  if (reader_.remaining() != 0) fail("the checkpoint has bytes this version does not know");
}

void CheckpointReader::fail(const std::string& message) const {
  throw InputError({path_, 0, 0, {}}, message);
}

void CheckpointReader::fail_read(const ByteStreamError& error) const {
  if (error.kind() == ByteStreamError::Kind::long_array) fail("the checkpoint is corrupt (array count)");
  fail("the checkpoint is truncated");
}

}  // namespace candela
