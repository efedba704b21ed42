// The file format every checkpoint shares (SPEC §15: long runs checkpoint and resume): a magic
// line naming what the file holds, then fields in the byte format of io/byte_stream.h (raw
// native-endian bytes, doubles exactly), then an FNV-1a checksum of everything before it.
// Written atomically (a temporary file renamed into place: an interrupted write never replaces a
// good checkpoint); read back with the magic, every size and the checksum verified, failures as
// InputError naming the file.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "io/byte_stream.h"
#include "math/vector.h"

namespace candela {

class CheckpointWriter : public ByteWriter {
 public:
  explicit CheckpointWriter(std::string_view magic) : ByteWriter(magic) {}
  void put_colors(const std::vector<Color>& colors);  // the count, then r, g, b of each
  // Appends the checksum and writes the file atomically; throws std::runtime_error on failure.
  void write(const std::string& path) const;
};

class CheckpointReader {
 public:
  // Reads the whole file; InputError when it is missing, not this kind of checkpoint (magic) or
  // damaged (checksum).
  CheckpointReader(const std::string& path, std::string_view magic);
  CheckpointReader(const CheckpointReader&) = delete;
  CheckpointReader& operator=(const CheckpointReader&) = delete;

  // As ByteReader's; a read past the end is an InputError ("the checkpoint is truncated").
  template <typename T>
  T get() {
    try {
      return reader_.get<T>();
    } catch (const ByteStreamError& e) {
      fail_read(e);
    }
  }
  std::string get_string();
  std::vector<Color> get_colors();
  // Every byte before the checksum was read; InputError otherwise.
  void finish() const;
  [[noreturn]] void fail(const std::string& message) const;

 private:
  [[noreturn]] void fail_read(const ByteStreamError& error) const;
  std::string path_;
  Bytes bytes_;  // after the magic, without the checksum
  ByteReader reader_;
};

}  // namespace candela
