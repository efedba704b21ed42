// Bounding volume hierarchy (SPEC §5; 000 §5.7.1; Kay & Kajiya 1986 for the slab test):
// a binary tree of axis-aligned boxes built by binned SAH (accel/bvh_builder.h), flattened depth
// first, traversed front to back with a small stack.
//
// Parameters (scene keys): bvh.max_leaf_primitives (default 0 = automatic: 8 for a tree of mesh
// triangles only, 4 with other shapes): a node with more primitives is split, unless the SAH
// says a leaf of up to 16 is cheaper (a triangle tree is costed per packet of four); bvh.bins
// (default 32): SAH bins per axis; bvh.isa (default auto): the traversal's instruction set.
//
// Layout (depth first): the binary SAH tree is collapsed into eight-wide nodes (256 bytes): the
// boxes of up to eight children as floats rounded outward, lane by lane, tested eight at a time
// (AVX2, AVX-512) or four at a time (SSE) in float against a conservatively rounded ray (see
// SlabSetup in bvh.cpp for the proof that no box the exact segment meets is culled). A leaf
// child refers to ceil(n / 4) packets of 176 bytes, each holding four lanes' triangle vertices in
// float for a conservative SSE pre-test of the watertight edge functions (FloatShear in bvh.cpp:
// a lane is rejected only when its edge functions certainly have mixed signs) and the lanes'
// primitive and triangle ids. Surviving lanes run the exact test: for a mesh triangle its three
// vertices in double — the packet's floats when every vertex of the tree is a float, else the
// double copies kept beside the packets — tested with WatertightRay::intersect / distance (the
// same watertight computation as MeshTriangle, so t is bit-identical); every other shape through
// its Shape. Only the nearest hit's SurfaceHit is filled: a triangle's by fill_triangle_hit, the
// code MeshTriangle::intersect runs, from the lane's corners and the exact test's weights (its
// mesh's normals are prefetched when the hit is found); a shape's by its Shape. Unbounded
// primitives (planes) live in a separate list tested by every ray; what no ray can report
// (degenerate mesh triangles, copies of a lower-indexed triangle: reportable_primitives) is left
// out. Rays outside the float test's proven range (huge or non-finite values, tiny direction
// components) test every primitive instead.
//
// bvh-fast (BvhSettings::exact false): the same tree, packets and traversal with Embree's
// kind of tests: a lane's hit is the float Möller–Trumbore test in the form of Embree's Triangle4,
// on its packet's first vertex and edges (p[1], p[2] hold p1 − p0 and p2 − p0 in bvh-fast) and
// their normal, kept beside the packets (PacketNormals, 48 bytes a packet; FloatMoller in bvh.cpp,
// four lanes at once) instead of the float pre-test and the exact double test (no shear set-up per
// ray, no double test per lane), and a node's boxes the non-robust slab test (FastSlabs in
// accel/bvh_traversal.inc: no outward rounding); after a triangle's hit the boxes' far end is one
// float step above its float t, not the double slack above it. It leaves the contract of
// accel/accelerator.h: distances differ from the list's in float's last bits, a box or triangle
// grazed within float's error may be missed, a ray through an edge or a vertex shared by two
// triangles can pass between them (not watertight), and the copies per instruction set may differ
// in the last bit (the wide ones contract products into fused multiply-adds). Each hit's t is still
// tested against the ray's [t_min, t_max] in double, hits at the same float distance that both pass
// the float test still go to the lower primitive index, shapes still answer through their own
// tests, and secondary rays start farther off the surface (position_error, Scene::ray_offset). Rays
// starting beyond 1e18 of the origin, or scenes larger than that, test every primitive through its
// own exact test, as the list does (o / d would overflow float in the box test there).
// docs/accelerators.md shows the image differences, docs/benchmarks.md its speed against Embree's
// and the exact bvh's.
//
// Traversal: the children a ray enters are pushed farthest first with their (float, lower
// bound) entry distances and the nearest is visited; popped entries that start beyond the
// current nearest hit are skipped. Boxes are tested against [t_min, t] widened by a small
// relative and scene-scaled slack, so that a box is never culled when its primitive's own test
// could report a hit within the interval. Hits at the current best t are still tested
// (t_max = nextafter(best t)), and closer_hit keeps the lowest primitive index among equal t,
// as the contract in accel/accelerator.h asks.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "accel/accelerator.h"
#include "accel/bvh_memory.h"
#include "util/enum_names.h"

namespace candela {

struct TriangleMesh;

// The instruction set of the traversal's box test (the same traversal compiled for each; see
// accel/bvh_traversal.inc).
enum class BvhIsa { automatic, sse, avx2, avx512 };

inline constexpr auto kBvhIsaNames = enum_names<BvhIsa>(
    {{BvhIsa::automatic, "auto"}, {BvhIsa::sse, "sse"}, {BvhIsa::avx2, "avx2"}, {BvhIsa::avx512, "avx512"}});

// The widest instruction set this CPU (and its operating system) supports.
BvhIsa widest_bvh_isa();

// The scene file's "bvh" object.
struct BvhSettings {
  // A node with more is split (binned SAH); 0: 8 for a tree of triangles only, else 4.
  int max_leaf_primitives = 0;
  int bins = 32;  // SAH bins per axis (16 gave a 1 % higher SAH cost on dragon_100k and Igea)
  BvhIsa isa = BvhIsa::automatic;  // automatic: the widest the CPU supports
  // false: bvh-fast, float Möller–Trumbore leaf tests without the exact contract (see above).
  bool exact = true;
};

class Bvh final : public Accelerator {
 public:
  explicit Bvh(const BvhSettings& settings = {});

  void build(std::span<const Primitive> primitives) override;
  bool intersect(const Ray& ray, Intersection& intersection) const override;
  bool occluded(const Ray& ray) const override;
  std::string_view name() const override { return exact_ ? "bvh" : "bvh-fast"; }
  // bvh-fast: the origin and the vertices in float (2^-24 of |p| each) move a ray's own triangle
  // by about 2^-23 |p| / cos θ along it; 2^-18 covers grazing angles down to cos θ = 1/32.
  double position_error() const override { return exact_ ? 0.0 : 0x1p-18; }
  // Figures: nodes, leaves, depth, SAH cost, primitives per leaf (mean), unbounded primitives.
  AcceleratorReport report() const override;

  static constexpr int kWidth = 8;  // children per node
  // A node of the 8-wide tree (the binary SAH tree collapsed): the boxes of up to eight
  // children as floats rounded outward, stored lane by lane (bounds[row][child], rows lower x,
  // y, z, upper x, y, z) so that one SSE operation handles four; an unused lane holds an
  // empty box (lower +inf, upper -inf), which no ray enters.
  struct alignas(128) Node {  // four cache lines
    float bounds[6][kWidth];
    uint32_t child[kWidth];  // inner child: node index; leaf child: first packet
    uint16_t count[kWidth];  // leaf child: number of slots (>= 1); 0 for an inner child or none
  };
  static_assert(sizeof(Node) == 256);

  // Up to four lanes of a leaf: their triangles' vertices rounded to float, lane by lane
  // (p[vertex][axis][lane]), for the conservative float pre-test, and which primitive each lane
  // is; a shape's lane holds NaN vertices (never rejected). A leaf of n primitives has
  // ceil(n / 4) consecutive packets. When every triangle's vertices are floats already (the
  // benchmark's meshes, as Embree gets them), these floats are the exact test's vertices too
  // and nothing else is stored; otherwise the double vertices are kept in corners_ (one entry
  // per lane), read only by the triangles that survive the pre-test. bvh-fast keeps the edges
  // p1 − p0 and p2 − p0 (rounded to float from the float vertices) in p[1] and p[2].
  struct alignas(16) Packet {
    float p[3][3][4];
    uint32_t primitive[4];  // primitive index, | kShapeSlot for a shape; kShapeSlot when unused
    uint32_t triangle[4];   // the triangle's index in its mesh (unused for shapes)
  };
  static_assert(sizeof(Packet) == 176);
  // bvh-fast only: each packet's lanes' normals (p1 − p0) × (p2 − p0), in float from the
  // packet's floats, beside the packets (n[axis][lane]); Embree's Triangle4 keeps its normal too.
  struct alignas(16) PacketNormals {
    float n[3][4];
  };

 private:
  // A lane's triangle's vertices in double, when they are not all floats.
  struct Corners {
    Vec3 p[3];
  };
  // Packet lanes whose primitive goes through its Shape (not an inline triangle).
  static constexpr uint32_t kShapeSlot = 0x80000000u;

  // The exact vertices of a triangle lane.
  void lane_corners(uint32_t packet, int lane, Vec3& p0, Vec3& p1, Vec3& p2) const;
  bool occluded_in_tree(const Ray& ray) const;
  // Whether bvh-fast's box test stays in float's range for this ray (see above: within 1e18 of
  // the origin); bvh-fast's other rays test every primitive.
  bool in_fast_range(const Ray& ray) const;
  // The traversal for one instruction set (Isa 0 SSE, 1 AVX2, 2 AVX-512): an overload per set,
  // each defined by accel/bvh_traversal.inc inside that set's target region; Exact false is
  // bvh-fast's (its box and leaf tests).
  template <int Isa>
  struct IsaTag {};
  template <bool Exact>
  bool intersect_tree(IsaTag<0>, const Ray& ray, Intersection& intersection) const;
  template <bool Exact>
  bool intersect_tree(IsaTag<1>, const Ray& ray, Intersection& intersection) const;
  template <bool Exact>
  bool intersect_tree(IsaTag<2>, const Ray& ray, Intersection& intersection) const;
  template <bool Exact>
  bool occluded_tree(IsaTag<0>, const Ray& ray) const;
  template <bool Exact>
  bool occluded_tree(IsaTag<1>, const Ray& ray) const;
  template <bool Exact>
  bool occluded_tree(IsaTag<2>, const Ray& ray) const;
  void prefetch_child(uint32_t child, uint32_t count) const;
  void prefetch_corners(uint32_t packet) const;
  // Rays the float slab test is not proven for (huge or non-finite values): every primitive,
  // as the list does.
  bool intersect_all_slots(const Ray& ray, Intersection& intersection) const;
  bool occluded_all_slots(const Ray& ray) const;

  int max_leaf_primitives_;
  int bins_;
  BvhIsa isa_;
  bool exact_;
  std::span<const Primitive> primitives_;
  std::vector<Node, BvhAllocator<Node>> nodes_;
  std::vector<Packet, BvhAllocator<Packet>> packets_;
  std::vector<Corners, BvhAllocator<Corners>> corners_;  // four per packet; empty when the floats are exact
  std::vector<PacketNormals, BvhAllocator<PacketNormals>> normals_;  // one per packet, bvh-fast only
  std::size_t slot_count_ = 0;                                       // primitives in leaves
  std::size_t triangle_count_ = 0;                                   // of which mesh triangles
  std::vector<uint32_t> unbounded_;                                  // primitives with infinite bounds
  const TriangleMesh* only_mesh_ = nullptr;  // the mesh of every inline triangle, when only one
  double scene_scale_ = 0;                   // largest |coordinate| of the tree's bounds
  uint32_t tree_nodes_ = 0;                  // nodes of the binary tree, leaves included
  uint32_t leaves_ = 0;
  uint32_t depth_ = 0;
  double sah_cost_ = 0;
  uint32_t largest_coincident_group_ = 0;  // BvhBuildResult::largest_coincident_group
};

}  // namespace candela
