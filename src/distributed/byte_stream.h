// Messages between ranks as flat bytes: trivially copyable values and arrays of them, native
// endianness (every rank of a run is the same build on the same kind of machine), doubles bit for
// bit — what a rank sends is what the single-process code would have kept.
#pragma once

#include <cstddef>
#include <cstring>
#include <span>
#include <stdexcept>
#include <type_traits>
#include <vector>

namespace candela {

using Bytes = std::vector<std::byte>;

class ByteWriter {
 public:
  template <typename T>
  void put(const T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    const auto* raw = reinterpret_cast<const std::byte*>(&value);
    bytes_.insert(bytes_.end(), raw, raw + sizeof(T));
  }
  // The count, then the elements.
  template <typename T>
  void put_array(std::span<const T> values) {
    static_assert(std::is_trivially_copyable_v<T>);
    put<uint64_t>(values.size());
    const auto* raw = reinterpret_cast<const std::byte*>(values.data());
    bytes_.insert(bytes_.end(), raw, raw + values.size_bytes());
  }
  template <typename T>
  void put_array(const std::vector<T>& values) {
    put_array(std::span<const T>(values));
  }
  Bytes take() { return std::move(bytes_); }

 private:
  Bytes bytes_;
};

// Reads what a ByteWriter wrote; std::runtime_error if the message is shorter than asked for (a
// message from another build or a bug, never user input).
class ByteReader {
 public:
  explicit ByteReader(std::span<const std::byte> bytes) : bytes_(bytes) {}
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
    const auto count = get<uint64_t>();
    if (count > (bytes_.size() - at_) / sizeof(T)) throw std::runtime_error("distributed message: array past its end");
    std::vector<T> values(count);
    if (count > 0) std::memcpy(values.data(), bytes_.data() + at_, count * sizeof(T));  // (data() may be null)
    at_ += count * sizeof(T);
    return values;
  }
 private:
  void need(std::size_t size) const {
    if (size > bytes_.size() - at_) throw std::runtime_error("distributed message: shorter than expected");
  }
  std::span<const std::byte> bytes_;
  std::size_t at_ = 0;
};

}  // namespace candela
