#pragma once

#include "geometry/shape.h"

namespace candela {

// An infinite plane through point with the given normal (000 eq. 5-12/5-13). The normal is
// normalised; both sides are hit and the geometric normal is always the declared one. uv are
// the hit's coordinates relative to point along the orthonormal_basis(normal) axes (dpdu,
// dpdv), so dpdu x dpdv = normal. A ray parallel to the plane (also one lying in it) misses.
class Plane final : public Shape {
 public:
  Plane(const Vec3& point, const Vec3& normal);

  bool intersect(const Ray& ray, SurfaceHit& hit) const override;
  bool occluded(const Ray& ray) const override;
  bool hit_distance(const Ray& ray, double& t) const override;
  Bounds3 bounds() const override;
  std::string_view type_name() const override { return "plane"; }
  // The convex polygon (3 to 6 vertices) where the plane meets settings.clip, found on the
  // box's edges, as a fan; nothing when the plane misses the box or only touches it (an edge
  // or a corner), or when the box is empty or not finite.
  void tessellate(const TessellationSettings& settings, TriangleMesh& mesh) const override;

  const Vec3& point() const { return point_; }
  const Vec3& normal() const { return normal_; }

 private:
  // The hit distance, or infinity for none (a hit always has t < t_max <= infinity).
  double nearest_t(const Ray& ray) const;
  Vec3 point_;
  Vec3 normal_;
  Vec3 u_axis_;
  Vec3 v_axis_;
};

}  // namespace candela
