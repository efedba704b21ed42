#include "accel/bvh.h"

#include <emmintrin.h>  // SSE2, part of x86-64
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <new>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>

#include "accel/bvh_builder.h"
#include "geometry/triangle_mesh.h"

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace candela {

namespace {

constexpr int kLeafHardCap = 16;  // the SAH may keep up to this many in a leaf
constexpr std::size_t kStackSize =
    (Bvh::kWidth - 1) * 128 + Bvh::kWidth;  // depth below 128, at most 7 left per level
constexpr std::size_t kGrain = 4096;

// [t_min, t_max] is widened by this relative amount plus this much of the scene's scale, far
// more than any shape's rounding of its hit distance near a box face.
constexpr double kSlack = 0x1p-32;

// v rounded to float, then moved one step towards +inf when that rounding went below v (when
// up) or towards -inf when it went above (when down): branch-free on the bit pattern (the
// rounding direction is unpredictable). |v| <= FLT_MAX here.
float round_directed(double v, bool up) {
  const float f = static_cast<float>(v) + 0.0f;  // -0 becomes +0
  const double back = static_cast<double>(f);
  const uint32_t step = up ? (back < v) : (back > v);
  uint32_t bits;
  std::memcpy(&bits, &f, sizeof bits);
  // Away from zero is +1 on the magnitude, towards zero -1; +0 (bits 0) steps to ±denorm_min.
  const uint32_t negative = bits >> 31;
  const bool away = up != static_cast<bool>(negative) || bits == 0;
  if (bits == 0 && !up) bits = 0x80000000u;  // -0, so that +1 gives -denorm_min
  bits += away ? step : 0u - step;
  float result;
  std::memcpy(&result, &bits, sizeof result);
  return result;
}

float round_down(double v) {
  constexpr double kMax = std::numeric_limits<float>::max();
  if (v > kMax) return kMax;
  if (v < -kMax) return -std::numeric_limits<float>::infinity();
  return round_directed(v, false);
}

float round_up(double v) {
  constexpr double kMax = std::numeric_limits<float>::max();
  if (v > kMax) return std::numeric_limits<float>::infinity();
  if (v < -kMax) return -kMax;
  return round_directed(v, true);
}

double max_abs(const Vec3& v) {
  return std::max({std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)});
}

// What build() does with each primitive.
enum class Kind : uint8_t { unbounded, shape, triangle, never_hit };

// The per-ray constants of the float slab test (four lanes at a time).
//
// Why it never culls a box that the ray's segment [t_lo, t_hi] (the double interval the
// triangle tests need, widened by kSlack as before) meets: let t* in [t_lo, t_hi] be a point of
// the segment inside the box (exactly), so that near_a <= t* <= far_a on every axis, with
// near_a = (entry plane - o) / d and far_a = (exit plane - o) / d.
// - The origin is rounded to float towards the side that makes each plane distance smaller for
//   entry planes and larger for exit planes (directed rounding, per sign of d).
// - The reciprocal is rounded towards zero after scaling by 1 - 2^-21 for entry planes, away
//   from zero after scaling by 1 + 2^-21 for exit planes; with the two float roundings of
//   (plane - origin) * reciprocal, a computed entry lies in [x, x (1 - 2^-20)] of its
//   directed value x (a computed exit in [x, x (1 + 2^-20)]), so: a computed entry is <= t*
//   when near_a >= 0 and <= 0 (indeed <= t* + |t*| 2^-20) when near_a < 0; a computed exit is
//   >= t* when t* >= 0, else >= t* - |t*| 2^-20.
// - Hence max(t0, entries) <= min(t1, exits) + margin, with margin >= 2^-17 max(0, -t_lo) plus
//   a floor for underflow (an absolute error of at most 2^-149 per product).
// - Overflow: the float path is taken only when |origin| and the scene's scale are at most
//   1e30 and every direction component is 0 or in [1e-30, 1e30] with the largest >= 1e-6, so
//   that t* <= 2e36: a product overflowing to +inf (an entry) or -inf (an exit) then only culls
//   boxes that the segment cannot meet, and the other overflows are conservative.
// - d = ±0 gives a reciprocal of ±inf: (plane - origin) · inf is ±inf with the exact sign, or
//   NaN, which _mm_max_ps / _mm_min_ps (second operand on NaN) ignore.
// Other rays (never made by the renderer) test every primitive (intersect_all_slots).
struct FloatSlabs {
  __m128 origin_near[3], origin_far[3];
  __m128 inverse_near[3], inverse_far[3];
  std::size_t near_offset[3], far_offset[3];  // byte offsets of the rows in a Node
  float t0 = 0, margin = 0;

  // False when the ray is outside the proven range (see above).
  bool init(const Ray& ray, double t_lo) {
    double largest = 0;
    for (int axis = 0; axis < 3; ++axis) {
      const double o = ray.origin[axis], d = ray.direction[axis];
      if (!(std::fabs(o) <= 1e30)) return false;
      const double ad = std::fabs(d);
      if (!(d == 0 || (ad >= 1e-30 && ad <= 1e30))) return false;
      largest = std::max(largest, ad);
      const bool negative = std::signbit(d);
      const std::size_t lower = offsetof(Bvh::Node, bounds) + sizeof(float[Bvh::kWidth]) * axis;
      const std::size_t upper = lower + sizeof(float[Bvh::kWidth]) * 3;
      near_offset[axis] = negative ? upper : lower;
      far_offset[axis] = negative ? lower : upper;
      origin_near[axis] = _mm_set1_ps(negative ? round_down(o) : round_up(o));
      origin_far[axis] = _mm_set1_ps(negative ? round_up(o) : round_down(o));
      if (d == 0) {
        const float inf = std::copysign(std::numeric_limits<float>::infinity(), d);
        inverse_near[axis] = inverse_far[axis] = _mm_set1_ps(inf);
      } else {
        const double inv = 1.0 / d;
        const double shrunk = inv * (1.0 - 0x1p-21), grown = inv * (1.0 + 0x1p-21);
        inverse_near[axis] = _mm_set1_ps(negative ? round_up(shrunk) : round_down(shrunk));
        inverse_far[axis] = _mm_set1_ps(negative ? round_down(grown) : round_up(grown));
      }
    }
    if (!(largest >= 1e-6) || !(t_lo >= -1e30)) return false;
    t0 = round_down(t_lo);
    margin = round_up(0x1p-17 * std::max(0.0, -t_lo) + 1e-35);
    return true;
  }

  // The lanes whose box the ray meets within [t0, t1] (bit per lane); entries receives the
  // (conservative) entry distances.
  int hit(const Bvh::Node& node, __m128 t0v, __m128 t1v, float* entries) const {
    return hit4(node, 0, t0v, t1v, entries) | (hit4(node, 4, t0v, t1v, entries + 4) << 4);
  }

  // hit() for the four lanes from first.
  int hit4(const Bvh::Node& node, int first, __m128 t0v, __m128 t1v, float* entries) const {
    __m128 near[3], far[3];
    for (int axis = 0; axis < 3; ++axis) {
      const char* base = reinterpret_cast<const char*>(&node) + sizeof(float) * first;
      near[axis] =
          _mm_mul_ps(_mm_sub_ps(_mm_load_ps(reinterpret_cast<const float*>(base + near_offset[axis])),
                                origin_near[axis]),
                     inverse_near[axis]);
      far[axis] = _mm_mul_ps(
          _mm_sub_ps(_mm_load_ps(reinterpret_cast<const float*>(base + far_offset[axis])), origin_far[axis]),
          inverse_far[axis]);
    }
    // A tree of max / min (a NaN operand makes its pair NaN or drops one bound, then the outer
    // max / min drops that pair: only constraints are lost, never gained).
    const __m128 entry = _mm_max_ps(_mm_max_ps(near[1], near[2]), _mm_max_ps(near[0], t0v));
    const __m128 exit = _mm_min_ps(_mm_min_ps(far[1], far[2]), _mm_min_ps(far[0], t1v));
    _mm_store_ps(entries, entry);
    return _mm_movemask_ps(_mm_cmple_ps(entry, _mm_add_ps(exit, _mm_set1_ps(margin))));
  }
};

// The conservative float pre-test of the watertight triangle test (WatertightRay): the same
// sheared edge functions u, v, w in float, a lane rejected only when they certainly have mixed
// signs, which the exact test rejects too.
// Error bound: with S = scene scale + max |origin| (every vertex and the origin lie within S
// of 0) and |sx|, |sy| <= 1 (kz is the dominant axis), each float sheared coordinate differs
// from the real one by at most 8 · 2^-24 S (roundings of the vertex, the origin, the
// difference, sx, the product and the subtraction) <= delta = 2^-20 S (a factor 2 spare).
// With M the largest |float sheared coordinate| of the triangle, a float edge function differs
// from the real one by at most 4 delta M + 2 delta^2 + 2^-22 M^2 (and the double one by far
// less), so E = 8 delta M + 2^-20 M^2 + 4 delta^2 + 1e-30 covers both with room for the
// roundings of E itself. A lane whose values are NaN (a shape, or overflow) is never rejected.
struct FloatShear {
  __m128 origin[3];
  __m128 sx, sy;
  __m128 c1, c2, c3;  // E = M (c1 + c2 M) + c3
  int kx, ky, kz;

  FloatShear(const WatertightRay& ray, double scene_scale) : kx(ray.kx), ky(ray.ky), kz(ray.kz) {
    for (int axis = 0; axis < 3; ++axis) origin[axis] = _mm_set1_ps(static_cast<float>(ray.origin[axis]));
    sx = _mm_set1_ps(static_cast<float>(ray.sx));
    sy = _mm_set1_ps(static_cast<float>(ray.sy));
    const double scale = scene_scale + max_abs(ray.origin);
    if (scale <= 1e15) {
      const double delta = 0x1p-20 * scale;
      c1 = _mm_set1_ps(round_up(8 * delta));
      c2 = _mm_set1_ps(0x1p-20f);
      c3 = _mm_set1_ps(round_up(4 * delta * delta + 1e-30));
    } else {  // never reject
      c1 = c2 = _mm_setzero_ps();
      c3 = _mm_set1_ps(std::numeric_limits<float>::infinity());
    }
  }

  // Lanes that may hit (bit per lane).
  int candidates(const Bvh::Packet& packet) const {
    const __m128 abs_mask = _mm_castsi128_ps(_mm_set1_epi32(0x7fffffff));
    __m128 x[3], y[3];
    __m128 largest = _mm_setzero_ps();
    for (int v = 0; v < 3; ++v) {
      const __m128 z = _mm_sub_ps(_mm_load_ps(packet.p[v][kz]), origin[kz]);
      x[v] = _mm_sub_ps(_mm_sub_ps(_mm_load_ps(packet.p[v][kx]), origin[kx]), _mm_mul_ps(sx, z));
      y[v] = _mm_sub_ps(_mm_sub_ps(_mm_load_ps(packet.p[v][ky]), origin[ky]), _mm_mul_ps(sy, z));
      largest = _mm_max_ps(largest, _mm_max_ps(_mm_and_ps(x[v], abs_mask), _mm_and_ps(y[v], abs_mask)));
    }
    const __m128 u = _mm_sub_ps(_mm_mul_ps(x[2], y[1]), _mm_mul_ps(y[2], x[1]));
    const __m128 v = _mm_sub_ps(_mm_mul_ps(x[0], y[2]), _mm_mul_ps(y[0], x[2]));
    const __m128 w = _mm_sub_ps(_mm_mul_ps(x[1], y[0]), _mm_mul_ps(y[1], x[0]));
    const __m128 e = _mm_add_ps(_mm_mul_ps(largest, _mm_add_ps(c1, _mm_mul_ps(c2, largest))), c3);
    const __m128 minus_e = _mm_xor_ps(e, _mm_set1_ps(-0.0f));
    const __m128 negative =
        _mm_or_ps(_mm_or_ps(_mm_cmplt_ps(u, minus_e), _mm_cmplt_ps(v, minus_e)), _mm_cmplt_ps(w, minus_e));
    const __m128 positive = _mm_or_ps(_mm_or_ps(_mm_cmpgt_ps(u, e), _mm_cmpgt_ps(v, e)), _mm_cmpgt_ps(w, e));
    return ~_mm_movemask_ps(_mm_and_ps(negative, positive)) & 0xf;
  }
};

// Calls visit(slot) for every slot of the leaf packets [ref, ref + ceil(count / 4)) whose
// triangle survives the float pre-test (shapes always do), in slot order; stops and returns
// true as soon as visit does. Shared by the nearest-hit and the any-hit traversal. A packet
// without triangles (triangle_lanes 0: quads, spheres, boxes) skips the pre-test, and the ray's
// shear (shear(), made on first use) is never made for a ray that meets only shapes: on the
// 21-quad Cornell box that per-ray set-up made the tree 20 % slower than the plain list.
template <class PacketType, class SlotType, class Shear, class Visit>
inline bool visit_candidates(const PacketType* packets, const uint8_t* triangle_lanes, const SlotType* slots,
                             uint32_t ref, uint32_t count, Shear&& shear, Visit&& visit) {
  for (uint32_t first = 0; first < count; first += 4, ++ref) {
    const int used = (1 << std::min(4u, count - first)) - 1;
    int mask = triangle_lanes[ref] != 0 ? shear().candidates(packets[ref]) & used : used;
    while (mask != 0) {
      const SlotType& slot = slots[4 * std::size_t{ref} + __builtin_ctz(static_cast<unsigned>(mask))];
      mask &= mask - 1;
      if (visit(slot)) return true;
    }
  }
  return false;
}

// The double interval [t_lo, t_hi] every box test must cover: [t_min, t] widened by a small
// relative and scene-scaled slack, far more than any shape's rounding of its hit distance near
// a box face.
struct Slack {
  double slack;
  Slack(const Ray& ray, double scene_scale) : slack(kSlack * (max_abs(ray.origin) + scene_scale)) {}
  double down(double t) const { return t - (std::fabs(t) * kSlack + slack); }
  double up(double t) const { return t + (std::fabs(t) * kSlack + slack); }
};

// A value made on first use, without the zero fill std::optional's storage gets here (the
// large per-ray objects below are made for few rays, and filling them costs more than a node).
template <class T>
struct Lazy {
  static_assert(std::is_trivially_destructible_v<T>);
  union {
    T value;
  };
  bool ready = false;
  Lazy() {}
  template <class... Args>
  T& emplace(Args&&... args) {
    new (&value) T(std::forward<Args>(args)...);
    ready = true;
    return value;
  }
  explicit operator bool() const { return ready; }
  T* operator->() { return &value; }
  const T* operator->() const { return &value; }
  T& operator*() { return value; }
};

// A child still to visit.
struct Pending {
  float t_enter;
  uint32_t child;  // node index or first slot
  uint32_t count;  // 0 for a node
};

}  // namespace

void* bvh_allocate(std::size_t bytes) {
  constexpr std::size_t kLarge = std::size_t{1} << 20, kHuge = std::size_t{2} << 20;
  const std::size_t alignment = bytes >= kLarge ? kHuge : 128;  // Node is 128-byte aligned
  const std::size_t size = (std::max<std::size_t>(bytes, 1) + alignment - 1) / alignment * alignment;
  void* memory = std::aligned_alloc(alignment, size);
  if (!memory) throw std::bad_alloc();
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  if (alignment == kHuge) madvise(memory, size, MADV_HUGEPAGE);  // a hint; failure is harmless
#endif
  return memory;
}

void bvh_free(void* memory) noexcept {
  std::free(memory);
}

Bvh::Bvh(const BvhSettings& settings)
    : max_leaf_primitives_(settings.max_leaf_primitives), bins_(settings.bins) {
  if (max_leaf_primitives_ < 1 || max_leaf_primitives_ > 1024)
    throw std::invalid_argument("bvh.max_leaf_primitives must be in [1, 1024], got " +
                                std::to_string(max_leaf_primitives_));
  if (bins_ < 2 || bins_ > 256)
    throw std::invalid_argument("bvh.bins must be in [2, 256], got " + std::to_string(bins_));
}

void Bvh::build(std::span<const Primitive> primitives) {
  primitives_ = primitives;
  nodes_.clear();
  lane_slots_.clear();
  slot_count_ = 0;
  packets_.clear();
  packet_triangles_.clear();
  unbounded_.clear();
  only_mesh_ = nullptr;
  scene_scale_ = 0;
  tree_nodes_ = leaves_ = depth_ = 0;
  sah_cost_ = 0;
  const std::size_t count = primitives.size();
  if (count >= kShapeSlot) throw std::invalid_argument("BVH: too many primitives (at most 2^31 - 1)");

  std::vector<Bounds3> bounds(count);
  std::vector<Kind> kinds(count, Kind::never_hit);
  // Only the reportable primitives go in (degenerate triangles and repeated ones stay never_hit).
  const std::vector<uint32_t> reportable = reportable_primitives(primitives);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, reportable.size(), kGrain),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t r = range.begin(); r < range.end(); ++r) {
                        const uint32_t i = reportable[r];
                        const Shape* shape = primitives[i].shape;
                        bounds[i] = shape->bounds();
                        if (!bounds[i].is_finite() || bounds[i].empty()) {
                          kinds[i] = Kind::unbounded;
                        } else if (dynamic_cast<const MeshTriangle*>(shape)) {
                          kinds[i] = Kind::triangle;
                        } else {
                          kinds[i] = Kind::shape;
                        }
                      }
                    });

  std::vector<uint32_t> tree_primitive;
  std::vector<Bounds3> tree_bounds;
  for (std::size_t i = 0; i < count; ++i) {
    const auto index = static_cast<uint32_t>(i);
    switch (kinds[i]) {
      case Kind::unbounded:
        unbounded_.push_back(index);
        break;
      case Kind::shape:
      case Kind::triangle:
        tree_primitive.push_back(index);
        tree_bounds.push_back(bounds[i]);
        break;
      case Kind::never_hit:
        break;
    }
  }
  bounds = {};
  if (tree_primitive.empty()) return;
  bool first_mesh = true;
  for (uint32_t index : tree_primitive) {
    if (kinds[index] != Kind::triangle) continue;
    const TriangleMesh* mesh = &static_cast<const MeshTriangle*>(primitives[index].shape)->mesh();
    if (first_mesh)
      only_mesh_ = mesh;
    else if (mesh != only_mesh_)
      only_mesh_ = nullptr;
    first_mesh = false;
  }

  BvhBuildSettings settings;
  settings.max_leaf_primitives = max_leaf_primitives_;
  settings.max_leaf_hard = std::max(kLeafHardCap, max_leaf_primitives_);
  settings.bins = bins_;
  const BvhBuildResult tree = build_bvh(tree_bounds, settings);
  tree_bounds = {};
  tree_nodes_ = static_cast<uint32_t>(tree.nodes.size());
  leaves_ = tree.leaves;
  depth_ = tree.depth;
  sah_cost_ = tree.sah_cost;
  scene_scale_ = std::max(max_abs(tree.nodes[0].bounds.lower), max_abs(tree.nodes[0].bounds.upper));

  std::vector<Slot> slots_(tree.order.size());
  slot_count_ = slots_.size();
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, slots_.size(), kGrain),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t s = range.begin(); s < range.end(); ++s) {
                        const uint32_t index = tree_primitive[tree.order[s]];
                        Slot& slot = slots_[s];
                        if (kinds[index] != Kind::triangle) {
                          slot = {};
                          slot.primitive = index | kShapeSlot;
                          continue;
                        }
                        const auto* triangle = static_cast<const MeshTriangle*>(primitives[index].shape);
                        const TriangleMesh& mesh = triangle->mesh();
                        const auto& corners = mesh.triangles[triangle->triangle_index()];
                        slot = {mesh.positions[corners[0]], mesh.positions[corners[1]],
                                mesh.positions[corners[2]], index, triangle->triangle_index()};
                      }
                    });

  // Packets: each leaf's slots in groups of four, in leaf order.
  std::vector<uint32_t> packet_of(slots_.size());  // first packet of the leaf starting at a slot
  for (const BvhBuildNode& built : tree.nodes) {
    if (built.count == 0) continue;
    packet_of[built.index] = static_cast<uint32_t>(packets_.size());
    for (uint32_t first = built.index; first < built.index + built.count; first += 4) {
      Packet packet{};
      uint8_t triangle_lanes = 0;
      for (int lane = 0; lane < 4; ++lane) {
        const uint32_t s = first + static_cast<uint32_t>(lane);
        const bool used = s < built.index + built.count;
        lane_slots_.push_back(used ? slots_[s] : Slot{});
        if (used && !(slots_[s].primitive & kShapeSlot)) triangle_lanes |= uint8_t(1u << lane);
        for (int vertex = 0; vertex < 3; ++vertex) {
          for (int axis = 0; axis < 3; ++axis) {
            float value = std::numeric_limits<float>::quiet_NaN();
            if (used && !(slots_[s].primitive & kShapeSlot)) {
              const Slot& slot = slots_[s];
              const Vec3& p = vertex == 0 ? slot.p0 : vertex == 1 ? slot.p1 : slot.p2;
              value = static_cast<float>(p[axis]);
            }
            packet.p[vertex][axis][lane] = value;
          }
        }
      }
      packets_.push_back(packet);
      packet_triangles_.push_back(triangle_lanes);
    }
  }

  // Collapse the binary tree into eight-wide nodes, depth first: a node's children start as
  // the two children of a binary inner node, and the inner child of largest surface area is
  // replaced by its own two children until there are eight (or only leaves). A lone leaf gets
  // a node of its own.
  const auto half_area = [&](std::size_t built) {
    const Vec3 d = tree.nodes[built].bounds.diagonal();
    return d.x * d.y + d.y * d.z + d.z * d.x;
  };
  const auto empty_node = [] {
    Node node{};
    for (int lane = 0; lane < kWidth; ++lane) {
      for (int axis = 0; axis < 3; ++axis) {
        node.bounds[axis][lane] = std::numeric_limits<float>::infinity();
        node.bounds[axis + 3][lane] = -std::numeric_limits<float>::infinity();
      }
    }
    return node;
  };
  const auto set_lane = [&](Node& node, int lane, std::size_t built, uint32_t inner_index) {
    const BvhBuildNode& child = tree.nodes[built];
    for (int axis = 0; axis < 3; ++axis) {
      node.bounds[axis][lane] = round_down(child.bounds.lower[axis]);
      node.bounds[axis + 3][lane] = round_up(child.bounds.upper[axis]);
    }
    node.child[lane] = child.count > 0 ? packet_of[child.index] : inner_index;
    node.count[lane] = static_cast<uint16_t>(child.count);
  };
  if (tree.nodes[0].count > 0) {
    Node node = empty_node();
    set_lane(node, 0, 0, 0);
    nodes_.push_back(node);
  } else {
    nodes_.reserve(tree.nodes.size() / 2);
    const auto emit = [&](const auto& self, std::size_t built) -> uint32_t {
      const auto index = static_cast<uint32_t>(nodes_.size());
      nodes_.emplace_back();
      std::size_t kids[kWidth] = {built + 1, tree.nodes[built].index};
      int n = 2;
      while (n < kWidth) {
        int widest = -1;
        double widest_area = -1;
        for (int i = 0; i < n; ++i) {
          if (tree.nodes[kids[i]].count == 0 && half_area(kids[i]) > widest_area) {
            widest = i;
            widest_area = half_area(kids[i]);
          }
        }
        if (widest < 0) break;
        const std::size_t split = kids[widest];
        kids[widest] = split + 1;
        kids[n++] = tree.nodes[split].index;
      }
      Node node = empty_node();
      for (int lane = 0; lane < n; ++lane)
        set_lane(node, lane, kids[lane], tree.nodes[kids[lane]].count > 0 ? 0 : self(self, kids[lane]));
      nodes_[index] = node;
      return index;
    };
    emit(emit, 0);
  }
}

// Brings a child's first cache lines in while the nearer children are visited.
inline void Bvh::prefetch_child(uint32_t child, uint32_t count) const {
  const char* address = count == 0 ? reinterpret_cast<const char*>(&nodes_[child])
                                   : reinterpret_cast<const char*>(&packets_[child]);
  _mm_prefetch(address, _MM_HINT_T0);
  _mm_prefetch(address + 64, _MM_HINT_T0);
  _mm_prefetch(address + 128, _MM_HINT_T0);
  if (count != 0) {
    prefetch_lanes(child);
  } else {
    _mm_prefetch(address + 192, _MM_HINT_T0);
  }
}

// The exact data of a leaf's first four lanes (320 bytes), fetched together with its packet
// so that the two misses overlap.
inline void Bvh::prefetch_lanes(uint32_t packet) const {
  const char* lanes = reinterpret_cast<const char*>(&lane_slots_[4 * std::size_t{packet}]);
  for (int line = 0; line < 6; ++line) _mm_prefetch(lanes + 64 * line, _MM_HINT_T0);
}

bool Bvh::intersect_all_slots(const Ray& ray, Intersection& intersection) const {
  double best_t = ray.t_max;
  uint32_t best = std::numeric_limits<uint32_t>::max();
  SurfaceHit best_hit, hit;
  Ray test = ray;
  for (std::size_t i = 0; i < primitives_.size(); ++i) {
    const auto primitive = static_cast<uint32_t>(i);
    if (primitives_[i].shape->intersect(test, hit) && closer_hit(hit.t, primitive, best_t, best)) {
      best_t = hit.t;
      best = primitive;
      best_hit = hit;
      test.t_max = std::nextafter(hit.t, kInfinity);
    }
  }
  if (best == std::numeric_limits<uint32_t>::max()) return false;
  intersection.surface = best_hit;
  intersection.primitive = best;
  return true;
}

bool Bvh::occluded_all_slots(const Ray& ray) const {
  for (const Primitive& primitive : primitives_)
    if (primitive.shape->occluded(ray)) return true;
  return false;
}

bool Bvh::intersect(const Ray& ray, Intersection& intersection) const {
  const Slack slack(ray, scene_scale_);
  FloatSlabs slabs;
  if (!nodes_.empty() && !slabs.init(ray, slack.down(ray.t_min)))
    return intersect_all_slots(ray, intersection);

  double best_t = ray.t_max;
  uint32_t best = std::numeric_limits<uint32_t>::max();
  bool found = false, best_is_triangle = false;
  const Slot* best_slot = nullptr;
  TriangleIntersection best_triangle;  // its weights
  // A shape's hit goes to whichever of two buffers does not hold the best hit so far, so an
  // accepted hit is never copied (SurfaceHit is some 300 bytes: the copies and the zero fill of two
  // were a sixth of this function on a scene of quads): a scratch one, made when a shape is first
  // tested, and the result itself, written only once something has been found.
  Lazy<SurfaceHit> scratch;
  SurfaceHit* best_hit = nullptr;
  // Hits at exactly best_t must still be seen (a lower index wins the tie), so once something
  // is found the shape tests run with t_max just above best_t.
  Ray test = ray;
  // The per-ray part of every triangle test, made at the first leaf.
  Lazy<WatertightRay> sheared;
  Lazy<FloatShear> shear;
  const auto accept = [&](double t, uint32_t primitive) {
    best_t = t;
    best = primitive;
    found = true;
    test.t_max = std::nextafter(t, kInfinity);
    if (sheared) sheared->t_max = test.t_max;
  };
  const auto test_shape = [&](uint32_t primitive) {
    SurfaceHit* candidate = &intersection.surface;
    if (best_hit == nullptr || best_hit == &intersection.surface) {
      if (!scratch) scratch.emplace();
      candidate = &*scratch;
    }
    if (primitives_[primitive].shape->intersect(test, *candidate) &&
        closer_hit(candidate->t, primitive, best_t, best)) {
      accept(candidate->t, primitive);
      best_hit = candidate;
      best_is_triangle = false;
    }
  };

  for (uint32_t primitive : unbounded_) test_shape(primitive);

  if (!nodes_.empty()) {
    const __m128 t0v = _mm_set1_ps(slabs.t0);
    float t1 = round_up(slack.up(best_t));
    float t1_skip = t1 + slabs.margin;
    alignas(16) float entries[kWidth];
    Pending stack[kStackSize];
    std::size_t top = 0;
    uint32_t ref = 0, count = 0;
    while (true) {
      if (count == 0) {
        const Node& node = nodes_[ref];
        int mask = slabs.hit(node, t0v, _mm_set1_ps(t1), entries);
        if (mask != 0) {
          int lane = __builtin_ctz(static_cast<unsigned>(mask));
          mask &= mask - 1;
          if (mask == 0) {
            ref = node.child[lane];
            count = node.count[lane];
            continue;
          }
          const int second = __builtin_ctz(static_cast<unsigned>(mask));
          if ((mask & (mask - 1)) == 0) {  // two: push the farther, go on with the nearer
            const int swap = -static_cast<int>(entries[second] < entries[lane]);  // branch free
            const int near_lane = lane ^ ((lane ^ second) & swap), far_lane = lane ^ second ^ near_lane;
            prefetch_child(node.child[far_lane], node.count[far_lane]);
            stack[top++] = {entries[far_lane], node.child[far_lane], node.count[far_lane]};
            ref = node.child[near_lane];
            count = node.count[near_lane];
            continue;
          }
          // More: push them all, farthest first, and go on with the nearest.
          const std::size_t base = top;
          while (true) {
            const Pending pending{entries[lane], node.child[lane], node.count[lane]};
            prefetch_child(pending.child, pending.count);
            std::size_t k = top++;
            while (k > base && stack[k - 1].t_enter < pending.t_enter) {
              stack[k] = stack[k - 1];
              --k;
            }
            stack[k] = pending;
            if (mask == 0) break;
            lane = __builtin_ctz(static_cast<unsigned>(mask));
            mask &= mask - 1;
          }
          --top;
          ref = stack[top].child;
          count = stack[top].count;
          continue;
        }
      } else {
        prefetch_lanes(ref);
        const auto make_shear = [&]() -> const FloatShear& {
          if (!sheared) {
            sheared.emplace(ray);
            sheared->t_max = test.t_max;
            shear.emplace(*sheared, scene_scale_);
          }
          return *shear;
        };
        visit_candidates(
            packets_.data(), packet_triangles_.data(), lane_slots_.data(), ref, count, make_shear,
            [&](const Slot& slot) {
              if (!(slot.primitive & kShapeSlot)) {
                TriangleIntersection found_triangle;
                if (sheared->intersect(slot.p0, slot.p1, slot.p2, found_triangle) &&
                    closer_hit(found_triangle.t, slot.primitive, best_t, best)) {
                  accept(found_triangle.t, slot.primitive);
                  best_triangle = found_triangle;
                  best_is_triangle = true;
                  best_slot = &slot;
                  if (only_mesh_ && !only_mesh_->corner_normals.empty())  // for the fill below
                    _mm_prefetch(reinterpret_cast<const char*>(&only_mesh_->corner_normals[slot.triangle]),
                                 _MM_HINT_T0);
                }
              } else {
                test_shape(slot.primitive & ~kShapeSlot);
              }
              return false;
            });
        t1 = round_up(slack.up(best_t));
        t1_skip = t1 + slabs.margin;
      }
      // Pop the next child that still starts before the nearest hit.
      while (top > 0 && stack[top - 1].t_enter > t1_skip) --top;
      if (top == 0) break;
      --top;
      ref = stack[top].child;
      count = stack[top].count;
    }
  }

  if (!found) return false;
  if (best_is_triangle) {
    // Filled as the triangle's own Shape does (normals, uv), from the slot's copy of its
    // corners and the weights of the same computation as intersect_triangle's.
    const TriangleMesh& mesh =
        only_mesh_ ? *only_mesh_ : static_cast<const MeshTriangle*>(primitives_[best].shape)->mesh();
    // Every field is written, so filling the result directly equals filling a shape's hit.
    fill_triangle_hit(mesh, best_slot->triangle, best_slot->p0, best_slot->p1, best_slot->p2, best_triangle,
                      intersection.surface);
  } else if (best_hit != &intersection.surface) {
    intersection.surface = *best_hit;
  }
  intersection.primitive = best;
  return true;
}

bool Bvh::occluded_in_tree(const Ray& ray) const {
  const Slack slack(ray, scene_scale_);
  FloatSlabs slabs;
  if (!slabs.init(ray, slack.down(ray.t_min))) return occluded_all_slots(ray);
  const __m128 t0v = _mm_set1_ps(slabs.t0);
  const __m128 t1v = _mm_set1_ps(round_up(slack.up(ray.t_max)));
  Lazy<WatertightRay> sheared;  // made at the first leaf
  Lazy<FloatShear> shear;
  alignas(16) float entries[kWidth];
  Pending stack[kStackSize];
  std::size_t top = 0;
  uint32_t ref = 0, count = 0;
  while (true) {
    if (count == 0) {
      const Node& node = nodes_[ref];
      int mask = slabs.hit(node, t0v, t1v, entries);
      if (mask != 0) {
        int lane = __builtin_ctz(static_cast<unsigned>(mask));
        mask &= mask - 1;
        while (mask != 0) {
          stack[top++] = {0.0f, node.child[lane], node.count[lane]};
          prefetch_child(node.child[lane], node.count[lane]);
          lane = __builtin_ctz(static_cast<unsigned>(mask));
          mask &= mask - 1;
        }
        ref = node.child[lane];
        count = node.count[lane];
        continue;
      }
    } else {
      prefetch_lanes(ref);
      const auto make_shear = [&]() -> const FloatShear& {
        if (!sheared) {
          sheared.emplace(ray);
          shear.emplace(*sheared, scene_scale_);
        }
        return *shear;
      };
      if (visit_candidates(packets_.data(), packet_triangles_.data(), lane_slots_.data(), ref, count,
                           make_shear, [&](const Slot& slot) {
                             if (!(slot.primitive & kShapeSlot)) {
                               double t;
                               return sheared->distance(slot.p0, slot.p1, slot.p2, t);
                             }
                             return primitives_[slot.primitive & ~kShapeSlot].shape->occluded(ray);
                           }))
        return true;
    }
    if (top == 0) return false;
    --top;
    ref = stack[top].child;
    count = stack[top].count;
  }
}

bool Bvh::occluded(const Ray& ray) const {
  for (uint32_t primitive : unbounded_)
    if (primitives_[primitive].shape->occluded(ray)) return true;
  return !nodes_.empty() && occluded_in_tree(ray);
}

AcceleratorReport Bvh::report() const {
  AcceleratorReport report;
  report.figures = {
      {"nodes", static_cast<double>(tree_nodes_)},
      {"leaves", static_cast<double>(leaves_)},
      {"depth", static_cast<double>(depth_)},
      {"SAH cost", sah_cost_},
      {"primitives per leaf", leaves_ > 0 ? static_cast<double>(slot_count_) / leaves_ : 0.0},
      {"unbounded primitives", static_cast<double>(unbounded_.size())},
  };
  report.bytes = nodes_.size() * sizeof(Node) + lane_slots_.size() * sizeof(Slot) +
                 packets_.size() * (sizeof(Packet) + 1) + unbounded_.size() * sizeof(uint32_t);
  return report;
}

}  // namespace candela
