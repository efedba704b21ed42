// The BVH builder: how to split, kept apart from the node layout and traversal (accel/bvh.h),
// as Embree keeps its builders apart from its kernels (STYLE.md).
//
// Binned SAH (Wald 2007, "On fast Construction of SAH-based Bounding Volume Hierarchies"):
// centroids are binned into `bins` bins along each of the three axes, the split planes between
// bins are rated by the surface area heuristic
//   cost = traversal + intersection · (A_left · B(N_left) + A_right · B(N_right)) / A_node,
// B(n) = ceil(n / block_size) the tests a leaf of n costs (1 per reference, or 1 per packet of
// four when a SIMD pre-test tests four at once), and the best plane wins. A node with at most
// max_leaf_primitives references becomes a leaf; a larger one with at most max_leaf_hard
// references becomes a leaf too when the SAH says that splitting costs more than intersecting
// everything (intersection · B(N)). When every centroid
// coincides, the references are halved in index order (object median); below a depth of
// kSahMaxDepth the split is an object median on the longest centroid axis, so the depth stays
// bounded whatever the input. Large nodes bin in parallel and children build in parallel (TBB);
// the result does not depend on the thread count.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "accel/bvh_memory.h"
#include "math/bounds.h"

namespace candela {

struct BvhBuildSettings {
  int max_leaf_primitives = 4;  // split any node with more
  int max_leaf_hard = 16;       // never make a larger leaf
  int bins = 16;                // per axis; clamped to [2, 256]
  double traversal_cost = 1.0;
  double intersection_cost = 1.5;
  // References a leaf tests at once (SIMD lanes): the SAH counts a leaf of n references as
  // ceil(n / block_size) intersections (Embree's sahBlockSize).
  int block_size = 1;
};

// A node of the built tree, flattened depth first: an inner node's first child is the next
// node, its second child is at `index`; a leaf holds references order[index, index + count).
struct BvhBuildNode {
  Bounds3 bounds;
  uint32_t index = 0;
  uint32_t count = 0;  // 0 for inner nodes
  int axis = 0;        // split axis of an inner node (the axis of the chosen plane)
};

struct BvhBuildResult {
  BvhArray<BvhBuildNode> nodes;  // empty when there was nothing to build
  std::vector<uint32_t> order;   // reference indices (into the input) in leaf order
  uint32_t leaves = 0;
  uint32_t depth = 0;   // levels: a single leaf has depth 1
  double sah_cost = 0;  // the tree's SAH cost with the settings' costs, relative to the root
  // The most references whose centroids all coincide (no split can separate them: they are
  // halved in index order into leaves that every ray meeting one of them visits); 0 when no
  // such group is larger than a leaf.
  uint32_t largest_coincident_group = 0;
};

// Every bounds must be finite and non-empty. The maximum depth is below 128.
BvhBuildResult build_bvh(std::span<const Bounds3> bounds, const BvhBuildSettings& settings);

}  // namespace candela
