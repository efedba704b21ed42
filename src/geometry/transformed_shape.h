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

  const Shape& shape() const { return *shape_; }
  const Transform& object_to_world() const { return object_to_world_; }

 private:
  // The object-space ray and the factor object length / world length.
  Ray to_object(const Ray& ray, double& scale) const;
  std::unique_ptr<Shape> shape_;
  Transform object_to_world_;
  Transform world_to_object_;
};

}  // namespace candela
