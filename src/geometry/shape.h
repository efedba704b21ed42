// The Shape interface: one implementation per file, created by name (scene/shape_registry).
#pragma once

#include <string_view>

#include "geometry/surface_hit.h"
#include "math/bounds.h"
#include "math/ray.h"

namespace candela {

class Shape {
 public:
  virtual ~Shape() = default;

  // Nearest hit with ray.t_min < t < ray.t_max. ray.direction must be unit length.
  // Fills every field of hit (object_position = position unless transformed).
  virtual bool intersect(const Ray& ray, SurfaceHit& hit) const = 0;

  // Any hit with ray.t_min < t < ray.t_max.
  virtual bool occluded(const Ray& ray) const {
    SurfaceHit hit;
    return intersect(ray, hit);
  }

  // World-space bounds; unbounded shapes (plane) return infinite bounds.
  virtual Bounds3 bounds() const = 0;

  // The registry name ("sphere", "triangle", ...).
  virtual std::string_view type_name() const = 0;
};

}  // namespace candela
