#include "util/checkpoint_file.h"

#include <fstream>
#include <iterator>
#include <stdexcept>

#include "util/atomic_file.h"
#include "util/error.h"
#include "util/hash.h"

namespace candela {

void CheckpointWriter::put_string(const std::string& text) {
  put(static_cast<uint64_t>(text.size()));
  bytes_ += text;
}

void CheckpointWriter::put_colors(const std::vector<Color>& colors) {
  put(static_cast<uint64_t>(colors.size()));
  for (const Color& c : colors) {
    put(c.r);
    put(c.g);
    put(c.b);
  }
}

void CheckpointWriter::write(const std::string& path) {
  std::string file = bytes_;
  const uint64_t checksum = fnv1a_64(file);
  file.append(reinterpret_cast<const char*>(&checksum), sizeof(checksum));
  write_atomically(path, [&](const std::string& temporary) {
    std::ofstream out(temporary, std::ios::binary);
    out.write(file.data(), static_cast<std::streamsize>(file.size()));
    out.close();
    if (!out) throw std::runtime_error("cannot write the checkpoint " + path);
  });
}

CheckpointReader::CheckpointReader(const std::string& path, std::string_view magic) : path_(path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail("cannot open the checkpoint");
  bytes_.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  if (bytes_.compare(0, magic.size(), magic) != 0)
    fail("not a " + std::string(magic.substr(0, magic.find_last_not_of(" \n") + 1)) + " checkpoint");
  if (bytes_.size() < magic.size() + sizeof(uint64_t)) fail("the checkpoint is truncated");
  uint64_t checksum = 0;
  std::memcpy(&checksum, bytes_.data() + bytes_.size() - sizeof(checksum), sizeof(checksum));
  bytes_.resize(bytes_.size() - sizeof(checksum));
  if (checksum != fnv1a_64(bytes_)) fail("the checkpoint is corrupt (checksum mismatch: truncated or changed)");
  at_ = magic.size();
}

std::string CheckpointReader::get_string() {
  const auto size = get<uint64_t>();
  need(size);
  std::string text = bytes_.substr(at_, size);
  at_ += size;
  return text;
}

std::vector<Color> CheckpointReader::get_colors() {
  const auto count = get<uint64_t>();
  if (count > (bytes_.size() - at_) / (3 * sizeof(double))) fail("the checkpoint is corrupt (colour count)");
  std::vector<Color> colors(count);
  for (Color& c : colors) {
    c.r = get<double>();
    c.g = get<double>();
    c.b = get<double>();
  }
  return colors;
}

void CheckpointReader::finish() const {
  if (at_ != bytes_.size()) fail("the checkpoint has bytes this version does not know");
}

void CheckpointReader::need(std::size_t size) const {
  if (bytes_.size() - at_ < size) fail("the checkpoint is truncated");
}

void CheckpointReader::fail(const std::string& message) const { throw InputError({path_, 0, 0, {}}, message); }

}  // namespace candela
