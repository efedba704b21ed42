#include "accel/bvh_builder.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace candela {

namespace {

// Below this depth the split is always an object median: depth < kSahMaxDepth + 33 < 128.
constexpr uint32_t kSahMaxDepth = 48;
constexpr std::size_t kParallelBuild = 4096;     // build the two children in parallel above
constexpr std::size_t kParallelBinning = 32768;  // bin in parallel above
constexpr std::size_t kBinningGrain = 8192;
constexpr int kMaxBins = 256;

struct PrimRef {
  Vec3 lower, upper;
  uint32_t index;
  // Halved before adding so that huge coordinates cannot overflow.
  Vec3 centroid() const { return lower * 0.5 + upper * 0.5; }
};

Bounds3 ref_bounds(const PrimRef& ref) {
  return {ref.lower, ref.upper};
}

// Half the surface area (the SAH only needs ratios).
double half_area(const Bounds3& b) {
  if (b.empty()) return 0;
  const Vec3 d = b.diagonal();
  return d.x * d.y + d.y * d.z + d.z * d.x;
}

struct Bin {
  Bounds3 bounds;
  Bounds3 centroids;
  uint32_t count = 0;
  void add(const PrimRef& ref, const Vec3& centroid) {
    bounds.extend(ref_bounds(ref));
    centroids.extend(centroid);
    ++count;
  }
  void merge(const Bin& other) {
    bounds.extend(other.bounds);
    centroids.extend(other.centroids);
    count += other.count;
  }
};

// How centroids map to bins along each axis (an axis with a flat or non-finite centroid extent
// gets scale 0 and is not binned).
struct Binning {
  int bins = 0;
  Vec3 origin;
  double scale[3] = {0, 0, 0};

  Binning(const Bounds3& centroids, int bin_count) : bins(bin_count), origin(centroids.lower) {
    for (int axis = 0; axis < 3; ++axis) {
      const double extent = centroids.upper[axis] - centroids.lower[axis];
      const double s = bins / extent;
      scale[axis] = (extent > 0 && std::isfinite(s)) ? s : 0;
    }
  }
  bool usable(int axis) const { return scale[axis] > 0; }
  int bin(const Vec3& centroid, int axis) const {
    const int k = static_cast<int>((centroid[axis] - origin[axis]) * scale[axis]);
    return std::clamp(k, 0, bins - 1);
  }
};

struct BinSet {
  std::vector<Bin> bins;  // 3 × count
  explicit BinSet(int count) : bins(3 * static_cast<std::size_t>(count)) {}
  void merge(const BinSet& other) {
    for (std::size_t i = 0; i < bins.size(); ++i) bins[i].merge(other.bins[i]);
  }
};

struct Split {
  bool leaf = false;
  int axis = 0;
  std::size_t left_count = 0;
  Bounds3 left_bounds, left_centroids, right_bounds, right_centroids;
};

class Builder {
 public:
  Builder(BvhArray<PrimRef>& refs, BvhArray<BvhBuildNode>& nodes, const BvhBuildSettings& settings)
      : refs_(refs), nodes_(nodes), settings_(settings) {
    bins_ = std::clamp(settings.bins, 2, kMaxBins);
    max_leaf_ = static_cast<std::size_t>(std::max(1, settings.max_leaf_primitives));
    max_leaf_hard_ = std::max(max_leaf_, static_cast<std::size_t>(std::max(1, settings.max_leaf_hard)));
    block_size_ = static_cast<std::size_t>(std::max(1, settings.block_size));
  }

  // See BvhBuildResult::largest_coincident_group.
  uint32_t largest_coincident_group() const { return largest_coincident_group_.load(); }

  // Builds refs[begin, end) into the node at `slot`; its subtree uses slots
  // [slot, slot + 2 (end - begin) - 1).
  void build(std::size_t slot, std::size_t begin, std::size_t end, const Bounds3& bounds,
             const Bounds3& centroids, uint32_t depth) {
    BvhBuildNode& node = nodes_[slot];
    node.bounds = bounds;
    const std::size_t count = end - begin;
    const Split split = choose_split(begin, end, bounds, centroids, depth);
    if (split.leaf) {
      node.index = static_cast<uint32_t>(begin);
      node.count = static_cast<uint32_t>(count);
      node.axis = 0;
      return;
    }
    const std::size_t middle = begin + split.left_count;
    const std::size_t right_slot = slot + 2 * split.left_count;
    node.index = static_cast<uint32_t>(right_slot);
    node.count = 0;
    node.axis = split.axis;
    const auto left = [&] {
      build(slot + 1, begin, middle, split.left_bounds, split.left_centroids, depth + 1);
    };
    const auto right = [&] {
      build(right_slot, middle, end, split.right_bounds, split.right_centroids, depth + 1);
    };
    if (count >= kParallelBuild) {
      tbb::parallel_invoke(left, right);
    } else {
      left();
      right();
    }
  }

 private:
  // The intersection tests a leaf of n references costs.
  double blocks(std::size_t n) const { return static_cast<double>((n + block_size_ - 1) / block_size_); }

  Split choose_split(std::size_t begin, std::size_t end, const Bounds3& bounds, const Bounds3& centroids,
                     uint32_t depth) const {
    Split split;
    const std::size_t count = end - begin;
    if (count <= max_leaf_) {
      split.leaf = true;
      return split;
    }
    const Binning binning(centroids, bins_);
    if (depth >= kSahMaxDepth || !(binning.usable(0) || binning.usable(1) || binning.usable(2)))
      return median_split(begin, end, centroids);

    const BinSet set = bin(begin, end, binning);

    // Sweep from the right for the right-hand areas, then from the left.
    const double traversal = settings_.traversal_cost, intersection = settings_.intersection_cost;
    const double area = half_area(bounds);
    double best_cost = kInfinity;
    int best_axis = -1, best_plane = 0;
    std::vector<double> right_cost(static_cast<std::size_t>(bins_));
    for (int axis = 0; axis < 3; ++axis) {
      if (!binning.usable(axis)) continue;
      const Bin* bins = &set.bins[static_cast<std::size_t>(axis) * bins_];
      Bounds3 right;
      uint32_t right_n = 0;
      for (int b = bins_ - 1; b > 0; --b) {
        right.extend(bins[b].bounds);
        right_n += bins[b].count;
        right_cost[static_cast<std::size_t>(b)] = half_area(right) * blocks(right_n);
      }
      Bounds3 left;
      uint32_t left_n = 0;
      for (int plane = 1; plane < bins_; ++plane) {  // left = bins [0, plane)
        left.extend(bins[plane - 1].bounds);
        left_n += bins[plane - 1].count;
        if (left_n == 0 || left_n == count) continue;
        // Unnormalised by the node's area, so that flat or point-like nodes compare safely.
        const double cost = half_area(left) * blocks(left_n) + right_cost[static_cast<std::size_t>(plane)];
        if (cost < best_cost) {
          best_cost = cost;
          best_axis = axis;
          best_plane = plane;
        }
      }
    }
    if (best_axis < 0) return median_split(begin, end, centroids);

    const double split_cost = traversal * area + intersection * best_cost;
    const double leaf_cost = intersection * blocks(count) * area;
    if (count <= max_leaf_hard_ && leaf_cost <= split_cost) {
      split.leaf = true;
      return split;
    }

    // Partition by the same bin computation that binned, so the counts agree.
    auto first = refs_.begin() + static_cast<std::ptrdiff_t>(begin);
    auto last = refs_.begin() + static_cast<std::ptrdiff_t>(end);
    std::partition(first, last,
                   [&](const PrimRef& ref) { return binning.bin(ref.centroid(), best_axis) < best_plane; });
    const Bin* bins = &set.bins[static_cast<std::size_t>(best_axis) * bins_];
    Bin left, right;
    for (int b = 0; b < best_plane; ++b) left.merge(bins[b]);
    for (int b = best_plane; b < bins_; ++b) right.merge(bins[b]);
    split.axis = best_axis;
    split.left_count = left.count;
    split.left_bounds = left.bounds;
    split.left_centroids = left.centroids;
    split.right_bounds = right.bounds;
    split.right_centroids = right.centroids;
    return split;
  }

  BinSet bin(std::size_t begin, std::size_t end, const Binning& binning) const {
    const auto fill = [&](std::size_t from, std::size_t to, BinSet& set) {
      for (std::size_t i = from; i < to; ++i) {
        const PrimRef& ref = refs_[i];
        const Vec3 c = ref.centroid();
        for (int axis = 0; axis < 3; ++axis) {
          if (!binning.usable(axis)) continue;
          set.bins[static_cast<std::size_t>(axis) * bins_ + binning.bin(c, axis)].add(ref, c);
        }
      }
    };
    if (end - begin < kParallelBinning) {
      BinSet set(bins_);
      fill(begin, end, set);
      return set;
    }
    return tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(begin, end, kBinningGrain), BinSet(bins_),
        [&](const tbb::blocked_range<std::size_t>& range, BinSet set) {
          fill(range.begin(), range.end(), set);
          return set;
        },
        [](BinSet a, const BinSet& b) {
          a.merge(b);
          return a;
        });
  }

  // Halves the references: by centroid along the longest centroid axis, or in index order when
  // every centroid coincides.
  Split median_split(std::size_t begin, std::size_t end, const Bounds3& centroids) const {
    Split split;
    const std::size_t count = end - begin;
    if (count <= max_leaf_hard_ &&
        !(centroids.diagonal().x > 0 || centroids.diagonal().y > 0 || centroids.diagonal().z > 0)) {
      split.leaf = true;  // identical centroids: splitting cannot separate anything
      return split;
    }
    const Vec3 extent = centroids.diagonal();
    if (!(extent.x > 0 || extent.y > 0 || extent.z > 0)) note_coincident_group(count);
    split.axis = max_dimension(extent);
    split.left_count = count / 2;
    auto first = refs_.begin() + static_cast<std::ptrdiff_t>(begin);
    auto last = refs_.begin() + static_cast<std::ptrdiff_t>(end);
    auto middle = first + static_cast<std::ptrdiff_t>(split.left_count);
    if (extent[split.axis] > 0) {
      const int axis = split.axis;
      std::nth_element(first, middle, last, [axis](const PrimRef& a, const PrimRef& b) {
        const double ca = a.centroid()[axis], cb = b.centroid()[axis];
        return ca < cb || (ca == cb && a.index < b.index);
      });
    }
    for (auto it = first; it != middle; ++it) {
      split.left_bounds.extend(ref_bounds(*it));
      split.left_centroids.extend(it->centroid());
    }
    for (auto it = middle; it != last; ++it) {
      split.right_bounds.extend(ref_bounds(*it));
      split.right_centroids.extend(it->centroid());
    }
    return split;
  }

  // The largest group halved because its centroids coincide (the first split of a group is its
  // largest node; the maximum does not depend on the order the tasks run in).
  void note_coincident_group(std::size_t count) const {
    uint32_t seen = largest_coincident_group_.load(std::memory_order_relaxed);
    const auto value = static_cast<uint32_t>(count);
    while (value > seen &&
           !largest_coincident_group_.compare_exchange_weak(seen, value, std::memory_order_relaxed)) {
    }
  }

  mutable std::atomic<uint32_t> largest_coincident_group_ = 0;
  BvhArray<PrimRef>& refs_;
  BvhArray<BvhBuildNode>& nodes_;
  const BvhBuildSettings& settings_;
  int bins_;
  std::size_t max_leaf_;
  std::size_t max_leaf_hard_;
  std::size_t block_size_ = 1;
};

struct RootBounds {
  Bounds3 bounds, centroids;
};

}  // namespace

BvhBuildResult build_bvh(std::span<const Bounds3> bounds, const BvhBuildSettings& settings) {
  BvhBuildResult result;
  const std::size_t count = bounds.size();
  if (count == 0) return result;
  if (count >= (std::size_t{1} << 31))
    throw std::invalid_argument("BVH: too many primitives (at most 2^31 - 1)");

  BvhArray<PrimRef> refs(count);
  const RootBounds root = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, count, kBinningGrain), RootBounds{},
      [&](const tbb::blocked_range<std::size_t>& range, RootBounds acc) {
        for (std::size_t i = range.begin(); i < range.end(); ++i) {
          refs[i] = {bounds[i].lower, bounds[i].upper, static_cast<uint32_t>(i)};
          acc.bounds.extend(bounds[i]);
          acc.centroids.extend(refs[i].centroid());
        }
        return acc;
      },
      [](RootBounds a, const RootBounds& b) {
        a.bounds.extend(b.bounds);
        a.centroids.extend(b.centroids);
        return a;
      });

  // Sparse slots: a subtree over n references fits in 2n - 1 slots (every leaf holds one or
  // more), so both children can be placed before either is built.
  BvhArray<BvhBuildNode> sparse(2 * count - 1);
  Builder builder(refs, sparse, settings);
  builder.build(0, 0, count, root.bounds, root.centroids, 1);
  result.largest_coincident_group = builder.largest_coincident_group();

  // Compact depth first (first child next, second child at `index`) and measure the tree.
  result.order.resize(count);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, kBinningGrain),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t i = range.begin(); i < range.end(); ++i)
                        result.order[i] = refs[i].index;
                    });
  const double root_area = half_area(root.bounds);
  const auto relative_area = [&](const Bounds3& b) { return root_area > 0 ? half_area(b) / root_area : 1.0; };
  struct Pending {
    uint32_t slot;
    int64_t parent;  // dense index of the inner node whose second child this is, or -1
    uint32_t depth;
  };
  std::vector<Pending> stack{{0, -1, 1}};
  result.nodes = BvhArray<BvhBuildNode>(2 * count - 1);
  uint32_t dense_count = 0;
  while (!stack.empty()) {
    const Pending pending = stack.back();
    stack.pop_back();
    const uint32_t dense = dense_count++;
    if (pending.parent >= 0) result.nodes[static_cast<std::size_t>(pending.parent)].index = dense;
    const BvhBuildNode& node = sparse[pending.slot];
    result.nodes[dense] = node;
    result.depth = std::max(result.depth, pending.depth);
    if (node.count > 0) {
      ++result.leaves;
      result.sah_cost += settings.intersection_cost *
                         std::ceil(static_cast<double>(node.count) / std::max(1, settings.block_size)) *
                         relative_area(node.bounds);
    } else {
      result.sah_cost += settings.traversal_cost * relative_area(node.bounds);
      stack.push_back({node.index, dense, pending.depth + 1});
      stack.push_back({pending.slot + 1, -1, pending.depth + 1});
    }
  }
  result.nodes.shrink(dense_count);
  return result;
}

}  // namespace candela
