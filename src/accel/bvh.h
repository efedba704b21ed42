// Bounding volume hierarchy (SPEC §5; 000 §5.7.1; Kay & Kajiya 1986 for the slab test):
// a binary tree of axis-aligned boxes built by binned SAH (accel/bvh_builder.h), flattened depth
// first, traversed front to back with a small stack.
//
// Parameters (scene keys): bvh.max_leaf_primitives (default 4): a node with more primitives is
// split, unless the SAH says a leaf of up to 16 is cheaper; bvh.bins (default 16): SAH bins per
// axis.
//
// Node layout (64 bytes, one cache line, depth first): an inner node holds the boxes of its
// two children as floats rounded outward from the double bounds, stored lane by lane
// (lower x of both children, then lower y, ...) so that both boxes are tested at once with
// two-wide double arithmetic; then each child's reference (an inner child's node index, or a
// leaf's first slot) and slot count (0 for an inner child), and the split axis. A tree that is
// a single leaf gets one node whose second child is an empty box. Leaves index slots in leaf
// order: for a mesh triangle the slot holds its three world-space vertices, tested inline with
// the same watertight intersect_triangle as MeshTriangle (so t is bit-identical); every other
// shape is tested through its Shape. Only the nearest hit's SurfaceHit is filled, by the
// primitive's own Shape. Unbounded primitives (planes) live in a separate list tested by every
// ray; degenerate mesh triangles, which never hit, are left out.
//
// Traversal: both children of a node are tested together; the one entered first is visited
// first and the other is pushed with its entry distance, and popped entries that start beyond
// the current nearest hit are skipped. The slab test takes "max of the entries, min of the
// exits" with NaN (0 · inf, a ray in a slab's plane) ignored, scales the exits by
// 1 + 4 gamma(3) (Ize 2013, "Robust BVH Ray Traversal") and widens [t_min, t] by a small
// relative and scene-scaled slack, so that a box is never culled when its primitive's own test
// could report a hit within the interval. Hits at the current best t are still tested
// (t_max = nextafter(best t)), and closer_hit keeps the lowest primitive index among equal t,
// as the contract in accel/accelerator.h asks.
#pragma once

#include <cstdint>
#include <vector>

#include "accel/accelerator.h"

namespace candela {

class Bvh final : public Accelerator {
 public:
  explicit Bvh(const AcceleratorSettings& settings = {});

  void build(std::span<const Primitive> primitives) override;
  bool intersect(const Ray& ray, Intersection& intersection) const override;
  bool occluded(const Ray& ray) const override;
  std::string_view name() const override { return "bvh"; }
  // Figures: nodes, leaves, depth, SAH cost, primitives per leaf (mean), unbounded primitives.
  AcceleratorReport report() const override;

  struct alignas(64) Node {
    // bounds[row][child]: rows lower x, y, z, upper x, y, z.
    float bounds[6][2];
    uint32_t child[2];  // inner child: node index; leaf child: first slot
    uint16_t count[2];  // leaf child: number of slots (>= 1); 0 for an inner child
    uint8_t axis;       // split axis
    uint8_t unused[3];
  };
  static_assert(sizeof(Node) == 64);

 private:
  // A leaf entry: an inline triangle (its vertices) or a primitive tested through its Shape.
  struct Slot {
    Vec3 p0, p1, p2;     // unused for shapes
    uint32_t primitive;  // primitive index, | kShapeSlot for shapes
  };
  // Slot entries whose primitive goes through its Shape (not an inline triangle).
  static constexpr uint32_t kShapeSlot = 0x80000000u;

  bool occluded_in_tree(const Ray& ray) const;

  int max_leaf_primitives_;
  int bins_;
  std::span<const Primitive> primitives_;
  std::vector<Node> nodes_;
  std::vector<Slot> slots_;
  std::vector<uint32_t> unbounded_;  // primitives with infinite bounds
  double scene_scale_ = 0;  // largest |coordinate| of the tree's bounds
  uint32_t tree_nodes_ = 0;  // nodes of the binary tree, leaves included
  uint32_t leaves_ = 0;
  uint32_t depth_ = 0;
  double sah_cost_ = 0;
};

}  // namespace candela
