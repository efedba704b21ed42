#include "io/checkpoint_file.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <type_traits>

#include "util/atomic_file.h"
#include "util/error.h"
#include "util/hash.h"
#include "util/input_file.h"

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

Bytes CheckpointWriter::seal() const {
  Bytes sealed = bytes();
  const uint64_t checksum = fnv1a_64(as_text(sealed));
  const auto* checksum_bytes = reinterpret_cast<const std::byte*>(&checksum);
  sealed.insert(sealed.end(), checksum_bytes, checksum_bytes + sizeof(checksum));
  return sealed;
}

void write_checkpoint_file(const std::string& path, const Bytes& sealed) {
  try {
    write_text_atomically(path, as_text(sealed));
  } catch (const std::exception&) {
    throw std::runtime_error("cannot write the checkpoint " + path);
  }
}

SealedCheckpoint read_checkpoint_file(const std::string& path) {
  const std::string file = read_input_file(path, "the checkpoint", kLargeInputLimit);
  SealedCheckpoint sealed{path, Bytes(file.size())};
  if (!file.empty()) std::memcpy(sealed.bytes.data(), file.data(), file.size());
  return sealed;
}

CheckpointReader::CheckpointReader(const SealedCheckpoint& sealed, std::string_view magic)
    : source_(sealed.source), reader_(fields_, "checkpoint") {
  const std::string_view file = as_text(sealed.bytes);
  if (file.compare(0, magic.size(), magic) != 0)
    fail("not a " + std::string(magic.substr(0, magic.find_last_not_of(" \n") + 1)) + " checkpoint");
  if (file.size() < magic.size() + sizeof(uint64_t)) fail("the checkpoint is truncated");
  uint64_t checksum = 0;
  std::memcpy(&checksum, file.data() + file.size() - sizeof(checksum), sizeof(checksum));
  const std::string_view checked(file.data(), file.size() - sizeof(checksum));
  if (checksum != fnv1a_64(checked))
    fail("the checkpoint is corrupt (checksum mismatch: truncated or changed)");
  const std::string_view fields = checked.substr(magic.size());
  fields_.resize(fields.size());
  if (!fields.empty()) std::memcpy(fields_.data(), fields.data(), fields.size());
  reader_ = ByteReader(fields_, "checkpoint");
}

std::string CheckpointReader::get_string() {
  try {
    return reader_.get_string();
  } catch (const ByteStreamError& e) {
    fail_read(e);
  }
}

template <typename T>
std::vector<T> CheckpointReader::get_array(const char* counted) {
  try {
    return reader_.get_array<T>();
  } catch (const ByteStreamError& e) {
    if (e.kind() == ByteStreamError::Kind::long_array)
      fail(std::string("the checkpoint is corrupt (") + counted + " count)");
    fail_read(e);
  }
}

// A checksum proves the bytes are the ones written, not that they are sound: a sum that is
// NaN or infinite (a damaged run, or a file sealed by hand) would resume into a NaN image.
std::vector<Color> CheckpointReader::get_colors() {
  std::vector<Color> colors = get_array<Color>("color");
  for (std::size_t i = 0; i < colors.size(); ++i)
    for (int c = 0; c < 3; ++c)
      if (!std::isfinite(colors[i][c]))
        fail("the checkpoint is corrupt (color " + std::to_string(i) + " of " +
             std::to_string(colors.size()) + " is not finite)");
  return colors;
}

std::vector<double> CheckpointReader::get_doubles() {
  std::vector<double> values = get_array<double>("value");
  for (std::size_t i = 0; i < values.size(); ++i)
    if (!std::isfinite(values[i]))
      fail("the checkpoint is corrupt (value " + std::to_string(i) + " of " + std::to_string(values.size()) +
           " is not finite)");
  return values;
}

void CheckpointReader::finish() const {
  if (reader_.remaining() != 0) fail("the checkpoint has bytes this version does not know");
}

void CheckpointReader::fail(const std::string& message) const {
  throw InputError({source_, 0, 0, {}}, message);
}

void CheckpointReader::fail_read(const ByteStreamError& error) const {
  if (error.kind() == ByteStreamError::Kind::long_array) fail("the checkpoint is corrupt (array count)");
  fail("the checkpoint is truncated");
}

}  // namespace candela
