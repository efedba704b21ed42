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
  // Smooth meshes (shading_normal interpolated from vertex normals): Hanika 2021's shadow
  // terminator offset ("Hacking the shadow terminator", Ray Tracing Gems II ch. 4), the step
  // P' − P from the flat facet to the curved surface its vertex normals imply, for a ray leaving
  // on the geometric normal's side (outside) or the other (inside); zero elsewhere. Rays that
  // leave from P' see past the neighbouring facets where the shading normal says the light is
  // above the surface, so the terminator follows the shading normals, not the facets.
  bool interpolated_normal = false;
  Vec3 terminator_lift_outside, terminator_lift_inside;
  // The point a ray leaving on `side`'s side of the surface starts from (before SPEC §8's offset).
  Vec3 lifted_toward(const Vec3& side) const {
    return position + (dot(side, geometric_normal) >= 0 ? terminator_lift_outside : terminator_lift_inside);
  }
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
