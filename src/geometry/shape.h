// The Shape interface: one implementation per file, created by name (scene/shape_registry).
#pragma once

#include <string_view>

#include "geometry/surface_hit.h"
#include "math/bounds.h"
#include "math/ray.h"

namespace candela {

struct TriangleMesh;

// A point drawn on a shape's surface for next-event estimation toward an emitter (SPEC §12).
struct SurfaceSample {
  Vec3 position;
  Vec3 normal;     // unit, the geometric normal (outward / the declared side), as intersect reports
  double pdf = 0;  // density of the point: per unit area (sample_area) or per unit solid angle
                   // seen from the reference point (sample_from)
};

// How finely a curved shape becomes triangles (SPEC §9 the rasterizer, §10 radiosity meshing).
struct TessellationSettings {
  // Divisions of a full turn: sphere longitudes (and half as many latitudes), cylinder, cone,
  // disc and torus around their axis (the torus tube too). At least 3.
  int segments = 32;
  // Curved shapes keep their surface's area (geometry/tessellation.h): their points move out from
  // the centre or axis by the one factor that gives the inscribed polyhedron the surface's area
  // back. false: every point on the surface (an inscribed polyhedron, smaller by ≈ (2π/N)²/6).
  bool area_true = true;
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

  // The t intersect would report, bit for bit, without filling a hit: the accelerators test the
  // unbounded shapes (planes) on every ray and fill the hit of the nearest one only if nothing
  // closer turns up.
  virtual bool hit_distance(const Ray& ray, double& t) const {
    SurfaceHit hit;
    if (!intersect(ray, hit)) return false;
    t = hit.t;
    return true;
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

  // Sampling for area emitters (SPEC §12: quads, discs, spheres, mesh triangles...).
  // The surface area in world units; 0 when the shape cannot be sampled (the plane, unbounded).
  virtual double area() const { return 0; }
  // A point with density per unit area (uniform in area for the untransformed shapes; a
  // transformed shape's density follows its transform's local area scale). False when the shape
  // cannot be sampled.
  virtual bool sample_area(const Vec2& u, SurfaceSample& sample) const;
  // The area density sample_area draws a point with, at a hit on this shape (hit as intersect
  // fills it).
  virtual double pdf_area(const SurfaceHit& hit) const;
  // A point seen from reference with density per unit solid angle about reference (the sphere
  // samples the cone it subtends; the default converts sample_area's density by d²/|cos θ|).
  // False when nothing is sampled (or the point coincides with reference / is seen edge-on).
  virtual bool sample_from(const Vec3& reference, const Vec2& u, SurfaceSample& sample) const;
  // The solid-angle density sample_from draws the direction from reference toward hit with
  // (hit on this shape, found along that direction). Must match sample_from exactly (MIS).
  virtual double pdf_from(const Vec3& reference, const SurfaceHit& hit) const;
};

}  // namespace candela
