#pragma once

#include <memory>

#include "geometry/shape.h"
#include "math/transform.h"

namespace candela {

// A shape placed by an object-to-world transform. The ray is taken to object space and
// renormalised there; t is converted back, so shapes only ever see unit directions.
class TransformedShape final : public Shape {
 public:
  TransformedShape(std::unique_ptr<Shape> shape, const Transform& object_to_world);

  bool intersect(const Ray& ray, SurfaceHit& hit) const override;
  bool occluded(const Ray& ray) const override;
  Bounds3 bounds() const override;
  std::string_view type_name() const override { return shape_->type_name(); }
  // The shape's own tessellation moved by object_to_world (TriangleMesh::transform: the
  // winding stays on the normal's side under a mirroring transform). An unbounded shape (a
  // plane) is tessellated inside the object-space bounds of settings.clip, which cover more
  // than the box, and its triangles are then cut to the box itself in world space.
  void tessellate(const TessellationSettings& settings, TriangleMesh& mesh) const override;

  // Sampling (SPEC §12): the shape's own sample moved by object_to_world. With M the linear
  // part, an object area element dA with unit normal n becomes |det M|·|M^{-T} n| dA, so the
  // world density is the object density divided by that factor (pdf_area uses the object-space
  // normal a hit carries). area() is exact for a similarity (|det M|^{2/3} times the shape's),
  // for a box, and for any shape whose factor is constant over its samples (planar shapes);
  // otherwise (a curved shape under non-uniform scale or shear) it is a numerical estimate: the
  // midpoint rule on a 256×256 grid of sample_area's unit square, relative error about 1e-5
  // for smooth shapes (sphere, torus) and up to about 1e-3 when the factor jumps between parts
  // (the caps of a cylinder or cone). sample_area's density stays exact. A TransformedShape
  // inside another is sampled correctly only when the inner transform is a similarity.
  double area() const override { return area_; }
  bool sample_area(const Vec2& u, SurfaceSample& sample) const override;
  double pdf_area(const SurfaceHit& hit) const override;

  const Shape& shape() const { return *shape_; }
  const Transform& object_to_world() const { return object_to_world_; }

 private:
  // The object-space ray and the factor object length / world length.
  Ray to_object(const Ray& ray, double& scale) const;
  std::unique_ptr<Shape> shape_;
  Transform object_to_world_;
  Transform world_to_object_;
  // |det M| |M^{-T} n| for the object-space unit normal n: world area per object area.
  double area_scale(const Vec3& object_normal) const;
  double determinant_ = 1;  // |det M|
  double area_ = 0;
};

}  // namespace candela
