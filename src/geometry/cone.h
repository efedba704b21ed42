#pragma once

#include "geometry/axial_frame.h"
#include "geometry/shape.h"

namespace candela {

// A truncated cone like POV-Ray's cone { <base>, base_radius, <cap>, cap_radius [open] }; one
// radius may be 0 (a pointed cone). Same frame as the cylinder (base at the origin, axis along
// +z, t unchanged): the side x^2 + y^2 = (r0 + k z)^2, k = (r1 - r0) / height, is clipped to
// 0 <= z <= height, and when capped the ends with a radius > 0 are tested as closed discs.
// Normals are outward: on the side (cos φ, sin φ, -k) / sqrt(1 + k^2), at the apex along the
// axis away from the cone, -axis on the base cap, +axis on the top cap. A zero discriminant
// (a tangent ray, or a ray along the axis through the apex) counts as a hit, so that the axis
// ray from inside a pointed cone leaves through its apex. uv on the side: u = angle / 2π about
// the axis, v = z / height; on a cap as for the cylinder. dpdu x dpdv points outward.
class Cone final : public Shape {
 public:
  Cone(const Vec3& base, double base_radius, const Vec3& cap, double cap_radius, bool capped = true);

  bool intersect(const Ray& ray, SurfaceHit& hit) const override;
  bool occluded(const Ray& ray) const override;
  Bounds3 bounds() const override;
  std::string_view type_name() const override { return "cone"; }
  // The side as one band of segments quads (segments triangles about the apex of a pointed
  // cone, whose apex is one vertex), and when capped each end of radius > 0 as a fan of
  // segments triangles; uv as on a hit. The rims are shared with the caps (watertight).
  void tessellate(const TessellationSettings& settings, TriangleMesh& mesh) const override;
  // Sampling (SPEC §12): uniform in area; the side or a cap picked by area. On the side the
  // angle is uniform and the radius at the sampled height is sqrt(r0² + u (r1² − r0²)) (the
  // side's area up to a height grows as the square of the radius there), inverted exactly.
  double area() const override;
  bool sample_area(const Vec2& u, SurfaceSample& sample) const override;
  double pdf_area(const SurfaceHit& hit) const override;

  const Vec3& base() const { return frame_.base(); }
  const Vec3& cap() const { return cap_; }
  double base_radius() const { return base_radius_; }
  double cap_radius() const { return cap_radius_; }
  bool capped() const { return capped_; }

 private:
  enum class Part { kSide, kBaseCap, kTopCap };
  // The hit distance and part, or infinity for none.
  double nearest_t(const Ray& ray, Part& part) const;
  AxialFrame frame_;
  double base_radius_;
  Vec3 cap_;
  double cap_radius_;
  bool capped_;
  double slope_;  // k: the change of radius per unit of height
};

}  // namespace candela
