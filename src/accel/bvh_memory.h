// Memory for the BVH's large arrays and its builder's: 128-byte aligned, and on Linux a block of
// 1 MiB or more is 2 MiB aligned and marked for transparent huge pages. Random access over tens
// of MiB misses the TLB far less on huge pages, and a 128 MiB array takes 64 page faults instead
// of 32,768: on a virtual machine, where each fault is a few microseconds, the builder's arrays
// for a million triangles took 0.45 s of a 1.25 s build to zero-fill page by page.
#pragma once

#include <cstddef>
#include <memory>
#include <type_traits>

namespace candela {

// Throws std::bad_alloc.
void* bvh_allocate(std::size_t bytes);
void bvh_free(void* memory) noexcept;

template <class T>
struct BvhAllocator {
  using value_type = T;
  BvhAllocator() = default;
  template <class U>
  BvhAllocator(const BvhAllocator<U>&) {}
  T* allocate(std::size_t n) { return static_cast<T*>(bvh_allocate(n * sizeof(T))); }
  void deallocate(T* p, std::size_t) noexcept { bvh_free(p); }
  template <class U>
  bool operator==(const BvhAllocator<U>&) const {
    return true;
  }
};

// A fixed-capacity array of an implicit-lifetime type left uninitialised (no zero fill: every
// element is written before it is read, by the code that fills it, often in parallel, so the
// pages are first touched by the threads that use them). shrink() lowers the size in place.
template <class T>
class BvhArray {
  static_assert(std::is_trivially_copyable_v<T> && std::is_trivially_destructible_v<T>);

 public:
  BvhArray() = default;
  explicit BvhArray(std::size_t size) : data_(static_cast<T*>(bvh_allocate(size * sizeof(T)))), size_(size) {}

  T& operator[](std::size_t i) { return data_.get()[i]; }
  const T& operator[](std::size_t i) const { return data_.get()[i]; }
  T* data() { return data_.get(); }
  const T* data() const { return data_.get(); }
  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  T* begin() { return data(); }
  T* end() { return data() + size_; }
  const T* begin() const { return data(); }
  const T* end() const { return data() + size_; }
  void shrink(std::size_t size) {
    if (size < size_) size_ = size;
  }

 private:
  struct Free {
    void operator()(T* p) const noexcept { bvh_free(p); }
  };
  std::unique_ptr<T, Free> data_;
  std::size_t size_ = 0;
};

}  // namespace candela
