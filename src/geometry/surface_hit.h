#pragma once

#include "math/vector.h"

namespace candela {

// What a shape reports about a ray hit (SPEC §4: distance, position, geometric and shading
// normal, uv, dpdu/dpdv).
struct SurfaceHit {
  double t = 0;
  Vec3 position;
  Vec3 geometric_normal;  // unit; outward for closed shapes, the declared side for open ones
  Vec3 shading_normal;    // unit; interpolated normals for smooth meshes, else geometric
  Vec2 uv;
  Vec3 dpdu;
  Vec3 dpdv;
  Vec3 object_position;  // the hit in the shape's own coordinates (solid textures)
  // dpdu and dpdv in the shape's own coordinates, set by TransformedShape (bump mapping of
  // solid textures moves object_position along them); equal to dpdu, dpdv otherwise.
  // Likewise the geometric normal in the shape's own coordinates (the spherical mapping).
  bool transformed = false;
  Vec3 object_dpdu_, object_dpdv_, object_normal_;
  const Vec3& object_dpdu() const { return transformed ? object_dpdu_ : dpdu; }
  const Vec3& object_dpdv() const { return transformed ? object_dpdv_ : dpdv; }
  const Vec3& object_normal() const { return transformed ? object_normal_ : geometric_normal; }
};

}  // namespace candela
