#include "accel/bvh.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "accel/bvh_builder.h"
#include "geometry/triangle_mesh.h"

namespace candela {

namespace {

constexpr int kLeafHardCap = 16;        // the SAH may keep up to this many in a leaf
constexpr std::size_t kStackSize = 128;  // the builder keeps the depth below 128
constexpr std::size_t kGrain = 4096;

// Exits are scaled by this (Ize 2013: 1 + 2 gamma(3) covers the rounding of the slab
// distances; 2^-48 ≈ 32 ulps also covers the rounding of the scaled inverse).
constexpr double kExitScale = 1.0 + 0x1p-48;
// [t_min, t_max] is widened by this relative amount plus this much of the scene's scale, far
// more than any shape's rounding of its hit distance near a box face.
constexpr double kSlack = 0x1p-32;

float round_down(double v) {
  constexpr double kMax = std::numeric_limits<float>::max();
  if (v > kMax) return kMax;
  if (v < -kMax) return -std::numeric_limits<float>::infinity();
  float f = static_cast<float>(v);
  if (static_cast<double>(f) > v) f = std::nextafter(f, -std::numeric_limits<float>::infinity());
  return f;
}

float round_up(double v) {
  constexpr double kMax = std::numeric_limits<float>::max();
  if (v > kMax) return std::numeric_limits<float>::infinity();
  if (v < -kMax) return -kMax;
  float f = static_cast<float>(v);
  if (static_cast<double>(f) < v) f = std::nextafter(f, std::numeric_limits<float>::infinity());
  return f;
}

double max_abs(const Vec3& v) { return std::max({std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)}); }

// What build() does with each primitive.
enum class Kind : uint8_t { unbounded, shape, triangle, never_hit };

// Two lanes of doubles: both children of a node are tested at once (GCC/Clang vector
// extension; SSE2 on x86-64, scalar code elsewhere).
using Double2 = double __attribute__((vector_size(16)));
using Float2 = float __attribute__((vector_size(8)));
using Mask2 = long long __attribute__((vector_size(16)));

Double2 load2(const float* lanes) {
  Float2 f;
  std::memcpy(&f, lanes, sizeof f);
  return __builtin_convertvector(f, Double2);
}
Double2 broadcast(double v) { return Double2{v, v}; }

// The per-ray constants of the slab test.
struct RaySlabs {
  Double2 origin[3];
  Double2 inverse[3];
  Double2 inverse_exit[3];
  int entry[3];  // row of Node::bounds of the plane the ray enters by on each axis
  int exit[3];
  bool negative[3];
  double slack;  // absolute widening of [t_min, t]

  RaySlabs(const Ray& ray, double scene_scale) {
    for (int axis = 0; axis < 3; ++axis) {
      origin[axis] = broadcast(ray.origin[axis]);
      // 1 / ±0 = ±inf; (plane - origin) · inf is ±inf, or NaN when the ray lies in the plane,
      // which the max/min below ignore (the ray stays inside that slab).
      const double inv = 1.0 / ray.direction[axis];
      inverse[axis] = broadcast(inv);
      inverse_exit[axis] = broadcast(inv * kExitScale);
      negative[axis] = std::signbit(ray.direction[axis]);
      entry[axis] = negative[axis] ? axis + 3 : axis;
      exit[axis] = negative[axis] ? axis : axis + 3;
    }
    slack = kSlack * (max_abs(ray.origin) + scene_scale);
  }
  double widen_down(double t) const { return t - (std::fabs(t) * kSlack + slack); }
  double widen_up(double t) const { return t + (std::fabs(t) * kSlack + slack); }

  // Kay-Kajiya slab test of both children against [t0, t1]: the entry distances, and a lane
  // mask of the boxes hit. A NaN distance fails its comparison and leaves the bound as it was.
  Mask2 hit(const Bvh::Node& node, double t0, double t1, Double2& t_enter) const {
    t_enter = broadcast(t0);
    Double2 t_exit = broadcast(t1);
    for (int axis = 0; axis < 3; ++axis) {
      const Double2 near = (load2(node.bounds[entry[axis]]) - origin[axis]) * inverse[axis];
      const Double2 far = (load2(node.bounds[exit[axis]]) - origin[axis]) * inverse_exit[axis];
      t_enter = near > t_enter ? near : t_enter;
      t_exit = far < t_exit ? far : t_exit;
    }
    return t_enter <= t_exit;
  }
};

// A child still to visit.
struct Pending {
  double t_enter;
  uint32_t child;  // node index or first slot
  uint32_t count;  // 0 for a node
};

}  // namespace

Bvh::Bvh(const AcceleratorSettings& settings)
    : max_leaf_primitives_(settings.bvh_max_leaf_primitives), bins_(settings.bvh_bins) {
  if (max_leaf_primitives_ < 1 || max_leaf_primitives_ > 1024)
    throw std::invalid_argument("bvh.max_leaf_primitives must be in [1, 1024], got " +
                                std::to_string(max_leaf_primitives_));
  if (bins_ < 2 || bins_ > 256)
    throw std::invalid_argument("bvh.bins must be in [2, 256], got " + std::to_string(bins_));
}

void Bvh::build(std::span<const Primitive> primitives) {
  primitives_ = primitives;
  nodes_.clear();
  slots_.clear();
  unbounded_.clear();
  scene_scale_ = 0;
  tree_nodes_ = leaves_ = depth_ = 0;
  sah_cost_ = 0;
  const std::size_t count = primitives.size();
  if (count >= kShapeSlot) throw std::invalid_argument("BVH: too many primitives (at most 2^31 - 1)");

  std::vector<Bounds3> bounds(count);
  std::vector<Kind> kinds(count);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, kGrain),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t i = range.begin(); i < range.end(); ++i) {
                        const Shape* shape = primitives[i].shape;
                        bounds[i] = shape->bounds();
                        if (!bounds[i].is_finite() || bounds[i].empty()) {
                          kinds[i] = Kind::unbounded;
                        } else if (const auto* triangle = dynamic_cast<const MeshTriangle*>(shape)) {
                          kinds[i] = triangle->mesh().is_degenerate(triangle->triangle_index())
                                         ? Kind::never_hit
                                         : Kind::triangle;
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
      case Kind::unbounded: unbounded_.push_back(index); break;
      case Kind::shape:
      case Kind::triangle:
        tree_primitive.push_back(index);
        tree_bounds.push_back(bounds[i]);
        break;
      case Kind::never_hit: break;
    }
  }
  bounds = {};
  if (tree_primitive.empty()) return;

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

  // One Node per inner node of the built tree, in the same (depth-first) order; a lone leaf
  // gets a node of its own with an empty second child.
  std::vector<uint32_t> node_of(tree.nodes.size());
  uint32_t inner = 0;
  for (std::size_t i = 0; i < tree.nodes.size(); ++i)
    if (tree.nodes[i].count == 0) node_of[i] = inner++;
  const bool lone_leaf = inner == 0;
  nodes_.resize(lone_leaf ? 1 : inner);
  const auto set_child = [&](Node& node, int lane, std::size_t built) {
    const BvhBuildNode& child = tree.nodes[built];
    for (int axis = 0; axis < 3; ++axis) {
      node.bounds[axis][lane] = round_down(child.bounds.lower[axis]);
      node.bounds[axis + 3][lane] = round_up(child.bounds.upper[axis]);
    }
    node.child[lane] = child.count > 0 ? child.index : node_of[built];
    node.count[lane] = static_cast<uint16_t>(child.count);
  };
  if (lone_leaf) {
    Node& node = nodes_[0];
    node = {};
    set_child(node, 0, 0);
    for (int axis = 0; axis < 3; ++axis) {  // an empty box: never hit
      node.bounds[axis][1] = std::numeric_limits<float>::infinity();
      node.bounds[axis + 3][1] = -std::numeric_limits<float>::infinity();
    }
  } else {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, tree.nodes.size(), kGrain),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                        for (std::size_t i = range.begin(); i < range.end(); ++i) {
                          const BvhBuildNode& built = tree.nodes[i];
                          if (built.count > 0) continue;
                          Node& node = nodes_[node_of[i]];
                          node = {};
                          set_child(node, 0, i + 1);
                          set_child(node, 1, built.index);
                          node.axis = static_cast<uint8_t>(built.axis);
                        }
                      });
  }

  slots_.resize(tree.order.size());
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
                                mesh.positions[corners[2]], index};
                      }
                    });
}

bool Bvh::intersect(const Ray& ray, Intersection& intersection) const {
  double best_t = ray.t_max;
  uint32_t best = std::numeric_limits<uint32_t>::max();
  bool found = false, best_is_triangle = false;
  SurfaceHit best_hit, hit;
  // Hits at exactly best_t must still be seen (a lower index wins the tie), so once something
  // is found the shape tests run with t_max just above best_t.
  Ray test = ray;
  WatertightRay sheared(ray);  // the per-ray part of every triangle test
  const auto accept = [&](double t, uint32_t primitive) {
    best_t = t;
    best = primitive;
    found = true;
    test.t_max = sheared.t_max = std::nextafter(t, kInfinity);
  };

  for (uint32_t primitive : unbounded_) {
    if (primitives_[primitive].shape->intersect(test, hit) && closer_hit(hit.t, primitive, best_t, best)) {
      accept(hit.t, primitive);
      best_hit = hit;
      best_is_triangle = false;
    }
  }

  if (!nodes_.empty()) {
    const RaySlabs slabs(ray, scene_scale_);
    const double t0 = slabs.widen_down(ray.t_min);
    double t1 = slabs.widen_up(best_t);
    Pending stack[kStackSize];
    std::size_t top = 0;
    Pending current{t0, 0, 0};
    while (true) {
      if (current.count == 0) {
        const Node& node = nodes_[current.child];
        Double2 t_enter;
        const Mask2 mask = slabs.hit(node, t0, t1, t_enter);
        if (mask[0] && mask[1]) {
          // Nearer entry first; on a tie (both entered at t0) the ray's side of the split.
          const int first = t_enter[0] < t_enter[1]   ? 0
                            : t_enter[1] < t_enter[0] ? 1
                                                      : (slabs.negative[node.axis] ? 1 : 0);
          stack[top++] = {t_enter[1 - first], node.child[1 - first], node.count[1 - first]};
          current = {t_enter[first], node.child[first], node.count[first]};
          continue;
        }
        if (mask[0] || mask[1]) {
          const int lane = mask[0] ? 0 : 1;
          current = {t_enter[lane], node.child[lane], node.count[lane]};
          continue;
        }
      } else {
        const uint32_t end = current.child + current.count;
        for (uint32_t s = current.child; s < end; ++s) {
          const Slot& slot = slots_[s];
          if (!(slot.primitive & kShapeSlot)) {
            double t;
            if (sheared.distance(slot.p0, slot.p1, slot.p2, t) && closer_hit(t, slot.primitive, best_t, best)) {
              accept(t, slot.primitive);
              best_is_triangle = true;
            }
          } else {
            const uint32_t primitive = slot.primitive & ~kShapeSlot;
            if (primitives_[primitive].shape->intersect(test, hit) &&
                closer_hit(hit.t, primitive, best_t, best)) {
              accept(hit.t, primitive);
              best_hit = hit;
              best_is_triangle = false;
            }
          }
        }
        t1 = slabs.widen_up(best_t);
      }
      // Pop the next child that still starts before the nearest hit.
      while (top > 0 && stack[top - 1].t_enter > t1) --top;
      if (top == 0) break;
      current = stack[--top];
    }
  }

  if (!found) return false;
  if (best_is_triangle) {
    // The triangle's own Shape fills the hit (normals, uv); its test repeats the same
    // computation, so it finds the same t.
    Ray tight = ray;
    tight.t_max = std::nextafter(best_t, kInfinity);
    static_cast<const MeshTriangle*>(primitives_[best].shape)->intersect(tight, best_hit);
  }
  intersection.surface = best_hit;
  intersection.primitive = best;
  return true;
}

bool Bvh::occluded_in_tree(const Ray& ray) const {
  const RaySlabs slabs(ray, scene_scale_);
  const double t0 = slabs.widen_down(ray.t_min);
  const double t1 = slabs.widen_up(ray.t_max);
  const WatertightRay sheared(ray);
  Pending stack[kStackSize];
  std::size_t top = 0;
  Pending current{t0, 0, 0};
  while (true) {
    if (current.count == 0) {
      const Node& node = nodes_[current.child];
      Double2 t_enter;
      const Mask2 mask = slabs.hit(node, t0, t1, t_enter);
      if (mask[0] || mask[1]) {
        const int first = mask[0] ? 0 : 1;
        if (mask[0] && mask[1]) stack[top++] = {t_enter[1], node.child[1], node.count[1]};
        current = {t_enter[first], node.child[first], node.count[first]};
        continue;
      }
    } else {
      const uint32_t end = current.child + current.count;
      for (uint32_t s = current.child; s < end; ++s) {
        const Slot& slot = slots_[s];
        if (!(slot.primitive & kShapeSlot)) {
          double t;
          if (sheared.distance(slot.p0, slot.p1, slot.p2, t)) return true;
        } else if (primitives_[slot.primitive & ~kShapeSlot].shape->occluded(ray)) {
          return true;
        }
      }
    }
    if (top == 0) return false;
    current = stack[--top];
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
      {"primitives per leaf", leaves_ > 0 ? static_cast<double>(slots_.size()) / leaves_ : 0.0},
      {"unbounded primitives", static_cast<double>(unbounded_.size())},
  };
  report.bytes = nodes_.size() * sizeof(Node) + slots_.size() * sizeof(Slot) +
                 unbounded_.size() * sizeof(uint32_t);
  return report;
}

}  // namespace candela
