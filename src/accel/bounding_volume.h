// Per-object bounding volumes tested before the exact intersection (SPEC §5, 000 §5.7.1, 001):
// a sphere from the centroid and the farthest point, an axis-aligned box (slab test), and
// Kay-Kajiya slabs — pairs of parallel planes along 7 plane-set normals (the 3 axes and the 4
// cube diagonals).
#pragma once

#include <array>
#include <span>
#include <string_view>

#include "accel/accelerator.h"
#include "math/bounds.h"

namespace candela {

struct BoundingSphere {
  Vec3 center;
  double radius = 0;
  // 000 §5.7.1: the centroid of the points and the distance to the farthest one.
  static BoundingSphere around(std::span<const Vec3> points);
  // Does the ray meet the sphere within (t_min, t_max)?
  bool hit_by(const Ray& ray) const;
};

struct KayKajiyaSlabs {
  static const std::array<Vec3, 7> kNormals;  // unit
  std::array<double, 7> lower{}, upper{};     // extent of the object along each normal
  static KayKajiyaSlabs around(std::span<const Vec3> points);
  // Intersection of the 7 slabs' parametric intervals with (t_min, t_max) is non-empty.
  bool hit_by(const Ray& ray) const;
};

// Points whose convex hull contains the shape: the vertices of a triangle or polygon; for a
// sphere its extreme points along the 7 slab normals (so the slabs and the bounding sphere
// are exact); else the 8 corners of its box.
void bounding_points(const Shape& shape, std::vector<Vec3>& points);

// The volume around a run of primitives (one scene object).
class ObjectBound {
 public:
  ObjectBound(BoundingVolumeKind kind, std::span<const Primitive> primitives);
  bool hit_by(const Ray& ray) const;
  bool unbounded() const { return unbounded_; }

 private:
  BoundingVolumeKind kind_;
  bool unbounded_ = false;
  BoundingSphere sphere_;
  Bounds3 box_;
  KayKajiyaSlabs slabs_;
};

}  // namespace candela
