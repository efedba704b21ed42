#pragma once

#include "geometry/shape.h"

namespace candela {

// 000 §5.6.1: the geometric test with early exits. uv: u = longitude / 2π about +z from +x,
// v = 1 - polar angle / π (0 at the -z pole, 1 at the +z pole).
class Sphere final : public Shape {
 public:
  Sphere(const Vec3& center, double radius);

  bool intersect(const Ray& ray, SurfaceHit& hit) const override;
  bool occluded(const Ray& ray) const override;
  Bounds3 bounds() const override;
  std::string_view type_name() const override { return "sphere"; }
  // segments longitudes by max(2, segments / 2) latitude bands, uv as on a hit; one vertex at
  // each pole, whose corner u is the middle of its triangle's longitude band.
  void tessellate(const TessellationSettings& settings, TriangleMesh& mesh) const override;

  // Sampling (SPEC §12): uniform in area; from a reference outside, the cone of directions the
  // sphere subtends uniformly (pbrt-v4's construction of the point, robust near the silhouette),
  // from inside or on the surface (to within 1e-9 relative, so that a shading point on the
  // sphere computed just outside by rounding counts as on it) the area density converted to
  // solid angle.
  double area() const override;
  bool sample_area(const Vec2& u, SurfaceSample& sample) const override;
  double pdf_area(const SurfaceHit& hit) const override;
  bool sample_from(const Vec3& reference, const Vec2& u, SurfaceSample& sample) const override;
  double pdf_from(const Vec3& reference, const SurfaceHit& hit) const override;

  const Vec3& center() const { return center_; }
  double radius() const { return radius_; }

 private:
  // The hit distance or a negative value for none.
  double nearest_t(const Ray& ray) const;
  Vec3 center_;
  double radius_;
};

}  // namespace candela
