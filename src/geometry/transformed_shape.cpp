#include "geometry/transformed_shape.h"

namespace candela {

TransformedShape::TransformedShape(std::unique_ptr<Shape> shape, const Transform& object_to_world)
    : shape_(std::move(shape)),
      object_to_world_(object_to_world),
      world_to_object_(object_to_world.inverse()) {}

Ray TransformedShape::to_object(const Ray& ray, double& scale) const {
  Ray local;
  local.origin = world_to_object_.point(ray.origin);
  const Vec3 direction = world_to_object_.vector(ray.direction);
  scale = length(direction);
  local.direction = direction / scale;
  local.t_min = ray.t_min * scale;
  local.t_max = ray.t_max * scale;
  return local;
}

bool TransformedShape::intersect(const Ray& ray, SurfaceHit& hit) const {
  double scale = 1;
  const Ray local = to_object(ray, scale);
  if (!shape_->intersect(local, hit)) return false;
  hit.t /= scale;
  hit.object_position = hit.position;
  hit.position = object_to_world_.point(hit.position);
  hit.geometric_normal = normalize(object_to_world_.normal(hit.geometric_normal));
  hit.shading_normal = normalize(object_to_world_.normal(hit.shading_normal));
  hit.transformed = true;
  hit.object_dpdu_ = hit.dpdu;
  hit.object_dpdv_ = hit.dpdv;
  hit.object_normal_ = hit.geometric_normal;
  hit.dpdu = object_to_world_.vector(hit.dpdu);
  hit.dpdv = object_to_world_.vector(hit.dpdv);
  return true;
}

bool TransformedShape::occluded(const Ray& ray) const {
  double scale = 1;
  return shape_->occluded(to_object(ray, scale));
}

Bounds3 TransformedShape::bounds() const { return object_to_world_.bounds(shape_->bounds()); }

}  // namespace candela
