// Values as flat bytes: trivially copyable values and arrays of them, native endianness, doubles
// bit for bit. The one byte format of the messages between ranks (distributed/: every rank of a
// run is the same build on the same kind of machine, so what a rank sends is what the
// single-process code would have kept) and of the checkpoint files (io/checkpoint_file.h adds
// their magic line and checksum).
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

namespace candela {

using Bytes = std::vector<std::byte>;

class ByteWriter {
 public:
  ByteWriter() = default;
  // Starts with these bytes, as they are (no count): a file's magic line.
  explicit ByteWriter(std::string_view prefix) { put_raw(prefix.data(), prefix.size()); }

  template <typename T>
  void put(const T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    put_raw(&value, sizeof(T));
  }
  // The count, then the elements.
  template <typename T>
  void put_array(std::span<const T> values) {
    static_assert(std::is_trivially_copyable_v<T>);
    put<uint64_t>(values.size());
    put_raw(values.data(), values.size_bytes());
  }
  template <typename T>
  void put_array(const std::vector<T>& values) {
    put_array(std::span<const T>(values));
  }
  // The length, then the characters.
  void put_string(std::string_view text) {
    put<uint64_t>(text.size());
    put_raw(text.data(), text.size());
  }

  const Bytes& bytes() const { return bytes_; }
  Bytes take() { return std::move(bytes_); }

 private:
  void put_raw(const void* data, std::size_t size) {
    if (size == 0) return;  // (data may be null)
    const std::size_t at = bytes_.size();
    bytes_.resize(at + size);  // (not insert: GCC 12 warns falsely of an overflow for it)
    std::memcpy(bytes_.data() + at, data, size);
  }
  Bytes bytes_;
};

// What a ByteReader throws when the bytes end before what is asked for. The readers of files
// turn it into their own error (io/checkpoint_file.h: an InputError naming the file).
class ByteStreamError : public std::runtime_error {
 public:
  enum class Kind {
    short_value,  // a value, or a string's characters, past the end
    long_array,   // an array's count larger than the bytes left can hold
  };
  ByteStreamError(Kind kind, const std::string& message) : std::runtime_error(message), kind_(kind) {}
  Kind kind() const { return kind_; }

 private:
  Kind kind_;
};

// Reads what a ByteWriter wrote. A read past the end throws ByteStreamError, its message starting
// with `what` (a string that outlives the reader, as a literal does): "distributed message:
// shorter than expected" for messages between ranks, where that is another build or a bug, never
// user input.
class ByteReader {
 public:
  explicit ByteReader(std::span<const std::byte> bytes, std::string_view what = "distributed message")
      : bytes_(bytes), what_(what) {}

  template <typename T>
  T get() {
    static_assert(std::is_trivially_copyable_v<T>);
    need(sizeof(T));
    T value;
    std::memcpy(&value, bytes_.data() + at_, sizeof(T));
    at_ += sizeof(T);
    return value;
  }
  template <typename T>
  std::vector<T> get_array() {
    static_assert(std::is_trivially_copyable_v<T>);
    const auto count = get<uint64_t>();
    if (count > remaining() / sizeof(T))
      throw ByteStreamError(ByteStreamError::Kind::long_array, std::string(what_) + ": array past its end");
    std::vector<T> values(count);
    if (count > 0)
      std::memcpy(values.data(), bytes_.data() + at_, count * sizeof(T));  // (data() may be null)
    at_ += count * sizeof(T);
    return values;
  }
  std::string get_string() {
    const auto size = get<uint64_t>();
    need(size);
    std::string text(reinterpret_cast<const char*>(bytes_.data() + at_), size);
    at_ += size;
    return text;
  }

  // The bytes not read yet.
  std::size_t remaining() const { return bytes_.size() - at_; }

 private:
  void need(uint64_t size) const {
    if (size > remaining())
      throw ByteStreamError(ByteStreamError::Kind::short_value,
                            std::string(what_) + ": shorter than expected");
  }
  std::span<const std::byte> bytes_;
  std::string_view what_;
  std::size_t at_ = 0;
};

}  // namespace candela
