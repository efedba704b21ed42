// The file format every checkpoint shares (SPEC §15: long runs checkpoint and resume): a magic
// line naming what the file holds, then fields as raw native-endian bytes (doubles exactly), then
// an FNV-1a checksum of everything before it. Written atomically (a temporary file renamed into
// place: an interrupted write never replaces a good checkpoint); read back with the magic, every
// size and the checksum verified, failures as InputError naming the file.
#pragma once

#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "math/vector.h"

namespace candela {

class CheckpointWriter {
 public:
  explicit CheckpointWriter(std::string_view magic) : bytes_(magic) {}
  template <typename T>
  void put(const T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    char raw[sizeof(T)];
    std::memcpy(raw, &value, sizeof(T));
    bytes_.append(raw, sizeof(T));
  }
  void put_string(const std::string& text);
  void put_colors(const std::vector<Color>& colors);  // the count, then r, g, b of each
  // Appends the checksum and writes the file atomically; throws std::runtime_error on failure.
  void write(const std::string& path);

 private:
  std::string bytes_;
};

class CheckpointReader {
 public:
  // Reads the whole file; InputError when it is missing, not this kind of checkpoint (magic) or
  // damaged (checksum).
  CheckpointReader(const std::string& path, std::string_view magic);
  template <typename T>
  T get() {
    static_assert(std::is_trivially_copyable_v<T>);
    need(sizeof(T));
    T value;
    std::memcpy(&value, bytes_.data() + at_, sizeof(T));
    at_ += sizeof(T);
    return value;
  }
  std::string get_string();
  std::vector<Color> get_colors();
  // Every byte before the checksum was read; InputError otherwise.
  void finish() const;
  [[noreturn]] void fail(const std::string& message) const;

 private:
  void need(std::size_t size) const;
  std::string path_;
  std::string bytes_;  // without the checksum
  std::size_t at_ = 0;
};

}  // namespace candela
