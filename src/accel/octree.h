// Octree: non-uniform spatial subdivision (000 §5.7.2 "subdivizare spațială ne-uniformă";
// 001 "arbore octal"). The root is the cube around the scene (anchored at the scene's lower
// corner); a node is cut into 8 equal children while it holds more than K primitives and its
// depth is below D. A primitive goes into every child its bounds overlap (within the margin of
// accel/subdivision.h).
//
// Parameters: octree.max_primitives K (default 8), octree.max_depth D (default 10, at most 32).
// One guard against runaway memory (large primitives overlapping many children): a node is not
// cut when the children would hold more than 4 references per primitive, nor when the cut
// separates nothing (two or more children meet primitives and each of them meets all). So a leaf
// holds more than K primitives only at depth D or where cutting would not separate them.
//
// Layout: a flat node array; the 8 children of a node are consecutive (empty ones are empty
// leaves); a leaf's primitives are a range of one index array, ascending. Boxes are implicit
// (depth and integer cell coordinates), so a node is 12 bytes.
//
// Traversal: front to back, parametric (in the spirit of Revelles, Ureña and Lastra 2000): the
// interval [t_enter, t_exit] of a node is split at the t where the ray crosses the node's three
// mid-planes; the children met are pushed on a stack in reverse order. Each primitive is tested
// once per ray (mailbox); a hit counts as final only once the walk has passed its t (000 §5.7.2),
// i.e. when it is no farther than the exit of the current leaf. Unbounded primitives (planes)
// are tested on every ray. Results are identical to the brute-force list (accelerator.h).
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "accel/accelerator.h"
#include "math/bounds.h"

namespace candela {

class Octree final : public Accelerator {
 public:
  static constexpr int kMaxDepth = 32;
  // Cutting stops when the children would hold more references than this many per primitive.
  static constexpr int kMaxDuplication = 4;

  struct Node {
    uint32_t first = 0;  // internal: index of the first of 8 children; leaf: offset into indices
    uint32_t count = 0;  // the primitives of the node (internal nodes: before the cut)
    uint16_t depth = 0;
    uint16_t leaf = 1;
  };

  // Throws std::invalid_argument when max_primitives < 0 or max_depth is outside [0, 32].
  explicit Octree(int max_primitives = 8, int max_depth = 10);

  void build(std::span<const Primitive> primitives) override;
  bool intersect(const Ray& ray, Intersection& intersection) const override;
  bool occluded(const Ray& ray) const override;
  std::string_view name() const override { return "octree"; }
  AcceleratorReport report() const override;

  // Inspection (tests, reports). nodes()[0] is the root; empty for a scene without bounded
  // primitives.
  const std::vector<Node>& nodes() const { return nodes_; }
  std::span<const uint32_t> leaf_primitives(const Node& leaf) const {
    return std::span<const uint32_t>(indices_).subspan(leaf.first, leaf.count);
  }
  const Bounds3& root_bounds() const { return root_; }
  // The leaf holding a point (the root cube must contain it) and that leaf's box.
  const Node& leaf_at(const Vec3& point, Bounds3* box = nullptr) const;

 private:
  struct BuildNode;
  // The guard of the file comment, given the primitives of each child of a node holding count.
  static bool worth_cutting(const std::array<std::vector<uint32_t>, 8>& children, std::size_t count);
  void subdivide(BuildNode& node, std::vector<uint32_t> primitives, int depth,
                 std::array<uint32_t, 3> coordinates) const;
  void flatten(BuildNode& node, uint32_t slot);
  // The coordinate of the lower face of cell `coordinate` at depth (the root is one cell).
  double face(int axis, uint64_t coordinate, int depth) const {
    return root_.lower[axis] + static_cast<double>(coordinate) * cell_size_[depth];
  }
  // Calls visit(primitives of the leaf, t_enter, t_exit) for each non-empty leaf the ray
  // crosses within (ray.t_min, t_max), front to back, until visit returns true.
  template <typename Visit>
  void walk(const Ray& ray, double t_max, Visit&& visit) const;

  int max_primitives_;
  int max_depth_;
  std::span<const Primitive> primitives_;
  std::vector<Bounds3> bounds_;  // of every primitive, during the build only
  double margin_ = 0;
  std::vector<uint32_t> unbounded_;
  Bounds3 root_;
  double root_size_ = 0;
  std::array<double, kMaxDepth + 2> cell_size_{};  // root_size_ / 2^depth, exactly
  std::vector<Node> nodes_;
  std::vector<uint32_t> indices_;
};

}  // namespace candela
