// The byte format every checkpoint shares (SPEC §15: long runs checkpoint and resume): a magic
// line naming what it holds, then fields in the byte format of io/byte_stream.h (raw
// native-endian bytes, doubles exactly), then an FNV-1a checksum of everything before it. A method
// seals its state into these bytes and is given them back to continue (RenderRequest); only the
// caller touches files: write_checkpoint_file writes them atomically (a temporary file renamed
// into place: an interrupted write never replaces a good checkpoint), read_checkpoint_file reads
// them back. Reading verifies the magic, every size and the checksum; failures are InputErrors
// naming the checkpoint's source (the file).
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "io/byte_stream.h"
#include "math/vector.h"

namespace candela {

// A checkpoint's sealed bytes, and where they came from, which every error about them names (the
// file they were read from).
struct SealedCheckpoint {
  std::string source;
  Bytes bytes;
};

class CheckpointWriter : public ByteWriter {
 public:
  explicit CheckpointWriter(std::string_view magic) : ByteWriter(magic) {}
  void put_colors(const std::vector<Color>& colors);  // the count, then r, g, b of each
  // Everything put so far with the checksum appended.
  Bytes seal() const;
};

// Throws std::runtime_error "cannot write the checkpoint PATH" on failure (the old file stays).
void write_checkpoint_file(const std::string& path, const Bytes& sealed);
// The file's bytes as they are (a CheckpointReader checks them); InputError when it cannot be read.
SealedCheckpoint read_checkpoint_file(const std::string& path);

class CheckpointReader {
 public:
  // InputError when the bytes are not this kind of checkpoint (magic) or damaged (checksum).
  CheckpointReader(const SealedCheckpoint& sealed, std::string_view magic);
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
  std::vector<double> get_doubles();
  // Every byte before the checksum was read; InputError otherwise.
  void finish() const;
  [[noreturn]] void fail(const std::string& message) const;

 private:
  // An array; a count past the bytes left is "the checkpoint is corrupt (<counted> count)".
  template <typename T>
  std::vector<T> get_array(const char* counted);
  [[noreturn]] void fail_read(const ByteStreamError& error) const;
  std::string source_;
  Bytes fields_;  // after the magic, without the checksum
  ByteReader reader_;
};

}  // namespace candela
