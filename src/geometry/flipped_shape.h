// A shape with its normals reversed (the shapes' `"flip_normals": true`): the inside of
// a sphere, a cylinder or any closed shape becomes its front — what classic radiosity's
// one-sided patches need to model a room inside an analytic shape — and the side a dielectric
// is entered from swaps (an air bubble in water is a flipped sphere of index 1/1.33's inverse,
// i.e. the water's index with its normal turned in). Everything else is the shape's own: the
// surface, its area and sampling densities, its texture coordinates (and the object-space
// frame solid textures and the spherical mapping read, so a texture looks the same). The
// tessellation is the shape's with every triangle wound the other way and its corner normals
// reversed.
#pragma once

#include <memory>

#include "geometry/shape.h"

namespace candela {

class FlippedShape final : public Shape {
 public:
  explicit FlippedShape(std::unique_ptr<Shape> shape);

  bool intersect(const Ray& ray, SurfaceHit& hit) const override;
  bool occluded(const Ray& ray) const override { return shape_->occluded(ray); }
  Bounds3 bounds() const override { return shape_->bounds(); }
  std::string_view type_name() const override { return shape_->type_name(); }
  void tessellate(const TessellationSettings& settings, TriangleMesh& mesh) const override;
  double area() const override { return shape_->area(); }
  bool sample_area(const Vec2& u, SurfaceSample& sample) const override;
  double pdf_area(const SurfaceHit& hit) const override;
  bool sample_from(const Vec3& reference, const Vec2& u, SurfaceSample& sample) const override;
  double pdf_from(const Vec3& reference, const SurfaceHit& hit) const override;

  const Shape& shape() const { return *shape_; }

 private:
  std::unique_ptr<Shape> shape_;
};

}  // namespace candela
