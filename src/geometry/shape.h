// The Shape interface: one implementation per file, created by name (scene/shape_registry).
#pragma once

#include <string_view>

#include "geometry/surface_hit.h"
#include "math/bounds.h"
#include "math/ray.h"

namespace candela {

struct TriangleMesh;

// How finely a curved shape becomes triangles (SPEC §9 the rasterizer, §10 radiosity meshing).
struct TessellationSettings {
  // Divisions of a full turn: sphere longitudes (and half as many latitudes), cylinder, cone,
  // disc and torus around their axis (the torus tube too). At least 3.
  int segments = 32;
  // Where an unbounded shape (the plane) is cut: the plane's polygon inside this box.
  Bounds3 clip;
};

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

  // Appends triangles approximating the surface to mesh, in world coordinates: positions,
  // triangles wound counter-clockwise about the shape's geometric normal (outward for closed
  // shapes, the declared side for open ones), and corner uvs from the shape's own
  // parametrisation; corner normals are left to the caller (compute_corner_normals with a
  // crease angle, SPEC §9). Vertices on the surface; curved shapes by settings.segments.
  virtual void tessellate(const TessellationSettings& settings, TriangleMesh& mesh) const;
};

}  // namespace candela
