// The one interface every acceleration structure answers (SPEC §5): nearest hit and any hit.
//
// Contract, so that every accelerator returns the same hit as the brute-force list and images
// do not depend on the accelerator: a primitive's hit distance depends only on the ray and the
// primitive (each shape's own exact test); the nearest hit is the smallest t, and among equal t
// the lowest primitive index (see closer_hit). One registered accelerator leaves the contract on
// purpose: bvh-fast (AcceleratorEntry::exact false; accel/bvh.h), float triangle tests for speed.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "geometry/shape.h"
#include "util/enum_names.h"

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

// The tie rule of the contract above.
inline bool closer_hit(double t, uint32_t primitive, double best_t, uint32_t best_primitive) {
  return t < best_t || (t == best_t && primitive < best_primitive);
}

// The primitives an accelerator is built over, ascending: every one except those no ray can
// report, which every accelerator leaves out of its structure —
// - a zero-area mesh triangle: it is never hit;
// - a mesh triangle whose three corners are, bit for bit and in the same order, those of a
//   lower-indexed mesh triangle (a copy in another object, say): its hit distance is the same
//   (it depends only on the ray and the corners), so the lower index wins every tie. Ten
//   thousand copies of one triangle made every ray meeting them test them all.
// O(n log n) in the primitives (the corners are hashed and sorted).
std::vector<uint32_t> reportable_primitives(std::span<const Primitive> primitives);

// What the list tests per scene object before its primitives (accel/bounding_volume.h).
enum class BoundingVolumeKind { none, sphere, box, slabs };
inline constexpr auto kBoundingVolumeNames =
    enum_names<BoundingVolumeKind>({{BoundingVolumeKind::none, "none"},
                                    {BoundingVolumeKind::sphere, "sphere"},
                                    {BoundingVolumeKind::box, "box"},
                                    {BoundingVolumeKind::slabs, "slabs"}});

// Quality figures printed next to timings (STYLE.md habit 8): nodes, leaves, depth, SAH cost…
struct AcceleratorReport {
  std::vector<std::pair<std::string, double>> figures;
  uint64_t bytes = 0;  // memory held by the structure
  // What makes some rays slow (the scene's warnings: `candela render` and `bench` print them).
  std::vector<std::string> warnings;
  std::string text() const;
};

class Accelerator {
 public:
  virtual ~Accelerator() = default;
  // The primitives must outlive the accelerator. May run in parallel (TBB).
  virtual void build(std::span<const Primitive> primitives) = 0;
  // Nearest hit with ray.t_min < t < ray.t_max.
  virtual bool intersect(const Ray& ray, Intersection& intersection) const = 0;
  // Any hit with ray.t_min < t < ray.t_max.
  virtual bool occluded(const Ray& ray) const = 0;
  virtual std::string_view name() const = 0;
  virtual AcceleratorReport report() const { return {}; }
  // How far, relative to |p|, a ray's own surface at p may seem to lie from p in the hit
  // distances it reports, beyond the shapes' exact tests: 0 for the exact accelerators; bvh-fast
  // rounds the vertices and the ray's origin to float. Scene::ray_offset adds this much of |p|.
  virtual double position_error() const { return 0; }
};

}  // namespace candela
