#pragma once

#include "geometry/axial_frame.h"
#include "geometry/shape.h"

namespace candela {

// A finite cylinder like POV-Ray's cylinder { <base>, <cap>, radius [open] }: the ray is taken
// into a frame with the base at the origin and the axis along +z (a rotation and a translation,
// so t is unchanged), the side's quadratic is clipped to 0 <= z <= height and, when capped, the
// two end discs are tested. Normals are outward: the side radially, -axis on the base cap,
// +axis on the top cap. A ray tangent to the side does not hit it (as for the sphere, 000
// §5.6.1); the caps are closed discs (their rim hits). From inside, the far surface is hit.
// uv on the side: u = angle / 2π about the axis (from the first axis of
// orthonormal_basis(axis)), v = z / height. On a cap: u = angle / 2π counter-clockwise seen
// from outside, v = 1 - r / radius. dpdu x dpdv points outward everywhere.
class Cylinder final : public Shape {
 public:
  Cylinder(const Vec3& base, const Vec3& cap, double radius, bool capped = true);

  bool intersect(const Ray& ray, SurfaceHit& hit) const override;
  bool occluded(const Ray& ray) const override;
  Bounds3 bounds() const override;
  std::string_view type_name() const override { return "cylinder"; }
  // The side as one band of segments quads, and when capped each cap as a fan of segments
  // triangles about its centre; uv as on a hit. The rims are shared with the caps (watertight).
  void tessellate(const TessellationSettings& settings, TriangleMesh& mesh) const override;
  // Sampling (SPEC §12): uniform in area; the side or a cap picked by area, the side by
  // (angle, height) uniform, a cap by the concentric map.
  double area() const override;
  bool sample_area(const Vec2& u, SurfaceSample& sample) const override;
  double pdf_area(const SurfaceHit& hit) const override;

  const Vec3& base() const { return frame_.base(); }
  const Vec3& cap() const { return cap_; }
  double radius() const { return radius_; }
  bool capped() const { return capped_; }

 private:
  enum class Part { kSide, kBaseCap, kTopCap };
  // The hit distance and part, or infinity for none.
  double nearest_t(const Ray& ray, Part& part) const;
  AxialFrame frame_;
  Vec3 cap_;
  double radius_;
  bool capped_;
};

}  // namespace candela
