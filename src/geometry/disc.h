#pragma once

#include "geometry/shape.h"

namespace candela {

// A flat disc, or an annulus when inner_radius > 0, centred on center and facing normal
// (normalised). Like the plane both sides are hit and the geometric normal is the declared one;
// a ray parallel to the disc misses. The annulus is closed: inner_radius <= r <= radius hits.
// uv as in pbrt: u = angle / 2π counter-clockwise about the normal from the first axis of
// orthonormal_basis(normal), v = (radius - r) / (radius - inner_radius) (0 on the rim), so
// dpdu x dpdv points along the normal.
class Disc final : public Shape {
 public:
  Disc(const Vec3& center, const Vec3& normal, double radius, double inner_radius = 0);

  bool intersect(const Ray& ray, SurfaceHit& hit) const override;
  bool occluded(const Ray& ray) const override;
  Bounds3 bounds() const override;
  std::string_view type_name() const override { return "disc"; }
  // One ring of segments cells between the rim and the inner rim (a fan about one centre
  // vertex when inner_radius is 0), uv as on a hit.
  void tessellate(const TessellationSettings& settings, TriangleMesh& mesh) const override;
  // Sampling (SPEC §12): uniform in area by the concentric map, its radius ρ ∈ [0, 1] taken to
  // sqrt(inner² + ρ²(radius² − inner²)) on an annulus (still area preserving).
  double area() const override;
  bool sample_area(const Vec2& u, SurfaceSample& sample) const override;
  double pdf_area(const SurfaceHit& hit) const override;

  const Vec3& center() const { return center_; }
  const Vec3& normal() const { return normal_; }
  double radius() const { return radius_; }
  double inner_radius() const { return inner_radius_; }

 private:
  // The hit distance, or infinity for none (a hit always has t < t_max <= infinity).
  double nearest_t(const Ray& ray) const;
  Vec3 center_;
  Vec3 normal_;
  double radius_;
  double inner_radius_;
  Vec3 u_axis_;
  Vec3 v_axis_;
};

// The bounds of a disc of the given radius about center, perpendicular to the unit normal:
// along axis i it reaches radius * sqrt(1 - normal_i^2). Shared with the cylinder and cone caps.
Bounds3 disc_bounds(const Vec3& center, const Vec3& unit_normal, double radius);

// The normal, uv and derivatives of a hit on an end cap of a cylinder or cone: top caps face
// +axis, base caps -axis; u = phi/2π counter-clockwise seen from outside, v = 1 - r/radius.
// radial and tangent are the unit directions at angle phi about the axis.
void fill_cap_hit(bool top, const Vec3& axis, const Vec3& radial, const Vec3& tangent, double phi, double r,
                  double cap_radius, SurfaceHit& hit);

}  // namespace candela
