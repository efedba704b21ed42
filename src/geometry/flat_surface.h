// What every flat shape (plane, disc, polygon) shares: the ray-plane distance of 000 eq. 5-13
// and the parts of the hit record that follow from a constant normal.
#pragma once

#include "geometry/surface_hit.h"
#include "math/constants.h"
#include "math/ray.h"

namespace candela {

// 000 eq. 5-13, t = −(d + N·O)/(N·D) with d = −N·P0, written N·(P0 − O)/(N·D). Infinity when
// the ray is parallel to the plane or t is outside (t_min, t_max).
inline double plane_hit_distance(const Ray& ray, const Vec3& point_on_plane, const Vec3& normal) {
  const double denominator = dot(normal, ray.direction);
  if (denominator == 0) return kInfinity;
  const double t = dot(normal, point_on_plane - ray.origin) / denominator;
  return (t > ray.t_min && t < ray.t_max) ? t : kInfinity;
}

// Sets t, position, object_position and both normals; uv and derivatives are the shape's.
inline void fill_flat_hit(const Ray& ray, double t, const Vec3& normal, SurfaceHit& hit) {
  hit.t = t;
  hit.position = ray.at(t);
  hit.object_position = hit.position;
  hit.geometric_normal = normal;
  hit.shading_normal = normal;
}

}  // namespace candela
