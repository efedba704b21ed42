// The one interface every acceleration structure answers (SPEC §5): nearest hit and any hit.
#pragma once

#include <cstdint>
#include <span>
#include <string_view>

#include "geometry/shape.h"

namespace candela {

// A shape placed in the scene with its material and the scene-file object it came from
// (a mesh is one object of many triangles).
struct Primitive {
  const Shape* shape = nullptr;
  uint32_t material = 0;
  uint32_t object = 0;
};

struct Intersection {
  SurfaceHit surface;
  uint32_t primitive = 0;
};

class Accelerator {
 public:
  virtual ~Accelerator() = default;
  // The primitives must outlive the accelerator.
  virtual void build(std::span<const Primitive> primitives) = 0;
  virtual bool intersect(const Ray& ray, Intersection& intersection) const = 0;
  virtual bool occluded(const Ray& ray) const = 0;
  virtual std::string_view name() const = 0;
};

}  // namespace candela
