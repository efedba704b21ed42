// What the spatial subdivisions (uniform grid, octree; 000 §5.7.2) share: the split into
// bounded primitives (put into voxels) and unbounded ones (planes, tested on every ray), the
// safety margin of the voxel boundaries, the per-ray mailbox, and the nearest-hit bookkeeping of
// the accelerator contract (accelerator.h).
//
// Why a margin: a voxel is walked over the interval [t_enter, t_exit] that the traversal
// computes, while a primitive sits in the voxels its bounds overlap. A hit at t is trusted
// (000 §5.7.2: "the intersection lies inside the current voxel") when t <= t_exit, so every
// primitive hit at or before t_exit must have been in a voxel walked so far. With rounding (of
// the voxel boundaries, the traversal's t, a shape's own t) a hit point may stray a few ulps
// into the next voxel; every voxel therefore holds the primitives whose bounds come within
// `margin` of it, and the box that rays are clipped to is grown by the same margin.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "accel/accelerator.h"
#include "math/bounds.h"
#include "math/constants.h"
#include "math/next_up.h"

namespace candela::subdivision {

struct PrimitiveSplit {
  std::vector<uint32_t> bounded;    // ascending primitive indices
  std::vector<uint32_t> unbounded;  // infinite, empty or non-finite bounds: tested on every ray
  std::vector<Bounds3> bounds;      // of every primitive, by primitive index
  Bounds3 scene;                    // union of the bounded primitives' bounds (empty if none)
  double margin = 0;                // see the file comment
};

// Only the reportable primitives (reportable_primitives) are split; the others get empty bounds
// and are in neither list.
inline PrimitiveSplit split_primitives(std::span<const Primitive> primitives) {
  PrimitiveSplit split;
  split.bounds.assign(primitives.size(), Bounds3{});
  for (const uint32_t index : reportable_primitives(primitives)) {
    const Bounds3 bounds = primitives[index].shape->bounds();
    split.bounds[index] = bounds;
    if (bounds.is_finite() && !bounds.empty()) {
      split.bounded.push_back(index);
      split.scene.extend(bounds);
    } else {
      split.unbounded.push_back(index);
    }
  }
  if (!split.bounded.empty()) {
    const Vec3 extent = split.scene.diagonal();
    const double largest = std::max({extent.x, extent.y, extent.z});
    double magnitude = 0;
    for (int axis = 0; axis < 3; ++axis)
      magnitude = std::max({magnitude, std::abs(split.scene.lower[axis]), std::abs(split.scene.upper[axis])});
    split.margin = std::max({1e-6 * largest, 1e-12 * magnitude, 1e-200});
  }
  return split;
}

inline Bounds3 grown(const Bounds3& bounds, double margin) {
  const Vec3 grow{margin, margin, margin};
  return {bounds.lower - grow, bounds.upper + grow};
}

// The primitives already tested by one ray (mailboxing, Amanatides & Woo 1987): a set of
// primitive indices on the stack of one intersect/occluded call, so the shared accelerator stays
// const and thread-safe. Open addressing with linear probing; starts inline and moves to the
// heap when a ray meets many primitives.
class RayMailbox {
 public:
  RayMailbox() { inline_.fill(kEmpty); }
  RayMailbox(const RayMailbox&) = delete;
  RayMailbox& operator=(const RayMailbox&) = delete;

  // True the first time index is inserted (the primitive is to be tested), false after.
  bool insert(uint32_t index) {
    if (2 * (size_ + 1) > capacity()) grow();
    uint32_t* slots = heap_.empty() ? inline_.data() : heap_.data();
    for (std::size_t slot = hash(index);; slot = (slot + 1) & mask()) {
      if (slots[slot] == index) return false;
      if (slots[slot] == kEmpty) {
        slots[slot] = index;
        ++size_;
        return true;
      }
    }
  }

 private:
  static constexpr uint32_t kEmpty = std::numeric_limits<uint32_t>::max();
  static constexpr int kInlineBits = 6;

  std::size_t capacity() const { return std::size_t{1} << bits_; }
  std::size_t mask() const { return capacity() - 1; }
  std::size_t hash(uint32_t index) const {  // Fibonacci hashing: the top bits of the product
    return static_cast<std::size_t>((static_cast<uint64_t>(index) * 0x9E3779B97F4A7C15ULL) >> (64 - bits_));
  }
  void grow() {
    std::vector<uint32_t> old =
        heap_.empty() ? std::vector<uint32_t>(inline_.begin(), inline_.end()) : std::move(heap_);
    bits_ += 2;
    heap_.assign(capacity(), kEmpty);
    size_ = 0;
    for (uint32_t index : old)
      if (index != kEmpty) insert(index);
  }

  std::array<uint32_t, std::size_t{1} << kInlineBits> inline_;
  std::vector<uint32_t> heap_;
  int bits_ = kInlineBits;
  std::size_t size_ = 0;
};

// The nearest hit of one ray under the contract's tie rule. Each shape test runs with t_max just
// above the best t so far, so that a hit at the same t reaches closer_hit, which keeps the
// lowest primitive index; the t itself comes from the shape's own test.
class NearestHit {
 public:
  NearestHit(std::span<const Primitive> primitives, const Ray& ray, Intersection& result)
      : primitives_(primitives), probe_(ray), t_max_(ray.t_max), result_(result) {}

  void test(uint32_t index) {
    if (!primitives_[index].shape->intersect(probe_, hit_)) return;
    if (found_ && !closer_hit(hit_.t, index, best_t_, result_.primitive)) return;
    result_.surface = hit_;
    result_.primitive = index;
    best_t_ = hit_.t;
    found_ = true;
    probe_.t_max = std::min(t_max_, next_up(best_t_));
  }

  bool found() const { return found_; }
  double best_t() const { return best_t_; }
  // The t_max beyond which nothing can win any more.
  double search_limit() const { return probe_.t_max; }

 private:
  std::span<const Primitive> primitives_;
  Ray probe_;
  double t_max_;
  Intersection& result_;
  SurfaceHit hit_;
  double best_t_ = kInfinity;
  bool found_ = false;
};

}  // namespace candela::subdivision
