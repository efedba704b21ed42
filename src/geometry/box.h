#pragma once

#include "geometry/shape.h"

namespace candela {

// An axis-aligned box by the slab test (001: "volum incadrator paralelipipedic"). The box is a
// closed set, as in Bounds3::intersect: a ray that only touches it (along a face, through an
// edge or a corner) hits it where it first touches. From inside, the far face is hit. The
// normal is the outward normal of the face hit. uv: on a face perpendicular to axis k the
// other two coordinates scaled to [0,1], u along axis k+1 and v along k+2 (mod 3) on the upper
// face, swapped on the lower face, so that dpdu x dpdv always points outward.
class Box final : public Shape {
 public:
  Box(const Vec3& lower, const Vec3& upper);

  bool intersect(const Ray& ray, SurfaceHit& hit) const override;
  bool occluded(const Ray& ray) const override;
  Bounds3 bounds() const override;
  std::string_view type_name() const override { return "box"; }
  // Two triangles per face, counter-clockwise seen from outside, uv as on a hit; the faces
  // share the 8 corner vertices.
  void tessellate(const TessellationSettings& settings, TriangleMesh& mesh) const override;
  // Sampling (SPEC §12): uniform in area, a face picked by its area, the point exactly on it.
  double area() const override;
  bool sample_area(const Vec2& u, SurfaceSample& sample) const override;
  double pdf_area(const SurfaceHit& hit) const override;

  const Vec3& lower() const { return lower_; }
  const Vec3& upper() const { return upper_; }

 private:
  // The hit distance, or infinity for none; face is the axis (0-2) for a lower face and
  // axis + 3 for an upper face.
  double nearest_t(const Ray& ray, int& face) const;
  Vec3 lower_;
  Vec3 upper_;
};

}  // namespace candela
