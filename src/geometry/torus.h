#pragma once

#include "geometry/shape.h"

namespace candela {

// A torus about center: the circle of major_radius R perpendicular to axis (normalised),
// swept by a disc of minor_radius r. Both radii must be > 0; r >= R (a spindle torus, as
// POV-Ray allows) is accepted. In the frame where the axis is +z the surface is
// (x^2 + y^2 + z^2 + R^2 - r^2)^2 = 4 R^2 (x^2 + y^2). The ray's origin is first moved to where
// it enters the bounding sphere of radius R + r, which keeps the quartic's coefficients small,
// then every root is polished by Newton steps on the torus function itself. Normals are
// outward. Whether an exactly tangent ray (a double root) hits depends on rounding.
// uv: u = angle / 2π about the axis (from the first axis of orthonormal_basis(axis)),
// v = tube angle / 2π (0 on the outer equator, 1/4 on the +axis side); dpdu x dpdv points
// outward.
class Torus final : public Shape {
 public:
  Torus(const Vec3& center, const Vec3& axis, double major_radius, double minor_radius);

  bool intersect(const Ray& ray, SurfaceHit& hit) const override;
  bool occluded(const Ray& ray) const override;
  Bounds3 bounds() const override;
  std::string_view type_name() const override { return "torus"; }
  // segments cells around the axis by max(3, segments / 2) around the tube (the tube is
  // usually the thinner, and the error of both falls as 1 / segments²), uv as on a hit;
  // both seams (u and v) are shared vertices, so the mesh is closed.
  void tessellate(const TessellationSettings& settings, TriangleMesh& mesh) const override;
  // Sampling (SPEC §12), exact and uniform in area for a ring or horn torus (r <= R): the angle
  // about the axis uniform, the tube angle θ with density (R + r cos θ)/(2πR), whose cdf
  // (Rθ + r sin θ)/(2πR) is inverted by safeguarded Newton steps (bisection when a step leaves
  // the bracket; at most 64 iterations, converging to rounding in about five). A spindle torus
  // (r > R) intersects itself and its intersect() normal does not follow the (θ, φ)
  // parametrisation, so it is not sampled: area() 0, sample_area false.
  double area() const override;
  bool sample_area(const Vec2& u, SurfaceSample& sample) const override;
  double pdf_area(const SurfaceHit& hit) const override;

  const Vec3& center() const { return center_; }
  const Vec3& axis() const { return axis_; }
  double major_radius() const { return major_radius_; }
  double minor_radius() const { return minor_radius_; }

 private:
  // The hit distance, or infinity for none; local is the hit in the torus frame.
  double nearest_t(const Ray& ray, Vec3& local) const;
  Vec3 to_local(const Vec3& v) const { return {dot(v, x_axis_), dot(v, y_axis_), dot(v, axis_)}; }
  // The implicit function (negative inside the tube) and its gradient, in the torus frame.
  double implicit(const Vec3& p) const;
  Vec3 gradient(const Vec3& p) const;
  Vec3 center_;
  Vec3 axis_;
  double major_radius_;
  double minor_radius_;
  Vec3 x_axis_;
  Vec3 y_axis_;
};

}  // namespace candela
