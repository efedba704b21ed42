// The Embree adapter (SPEC §5: "an Embree adapter (optional at build time) for comparison"),
// built only when CMake finds Embree 3 (CANDELA_HAVE_EMBREE). Two modes:
//
// - exact (the default; `render.accelerator: "embree"`): Embree's BVH over the bounds of every
//   primitive (RTC_GEOMETRY_TYPE_USER) whose intersect/occluded callbacks call our own shape
//   tests in double precision, so hits are identical to the brute-force list, ties included
//   (closer_hit). Embree traverses with a float copy of the ray, so each box is inflated by a
//   margin that covers the float rounding of the ray and of Embree's arithmetic, the float ray
//   starts where the double ray enters the bounds of all primitives (keeping the rounding
//   small), and the float tfar is only a bound rounded up from the exact double distance kept
//   in a per-call context. Unbounded primitives (planes) are tested one by one afterwards.
//
// - native_triangles (`candela bench`, the reference speed): every primitive must be a
//   MeshTriangle of one mesh; the mesh goes to Embree as an RTC_GEOMETRY_TYPE_TRIANGLE
//   geometry with float32 vertices (primID = triangle index; triangles that are not
//   primitives become degenerate), RTC_SCENE_FLAG_NONE, RTC_BUILD_QUALITY_HIGH, single rays
//   through rtcIntersect1/rtcOccluded1 with Embree's own float triangle test. intersect() fills
//   Intersection.primitive with the triangle's primitive index and, of the surface, only t,
//   position, object_position, and the geometric and shading normal (Embree's Ng,
//   normalised); uv, dpdu and dpdv are left zero. Hits differ from the double tests on rays
//   grazing an edge (BENCH-RAYS.md).
//
// report().bytes counts what Embree allocated on this accelerator's device (a memory monitor
// callback) plus the adapter's own index tables.
#pragma once

#include <memory>

#include "accel/accelerator.h"

namespace candela {

class EmbreeAccelerator final : public Accelerator {
 public:
  enum class Mode { exact, native_triangles };

  // Throws std::runtime_error when Embree cannot create a device.
  explicit EmbreeAccelerator(Mode mode = Mode::exact);
  ~EmbreeAccelerator() override;
  EmbreeAccelerator(const EmbreeAccelerator&) = delete;
  EmbreeAccelerator& operator=(const EmbreeAccelerator&) = delete;

  // native_triangles: throws std::invalid_argument unless every primitive is a MeshTriangle
  // of the same mesh. Both: std::runtime_error when Embree reports an error.
  void build(std::span<const Primitive> primitives) override;
  bool intersect(const Ray& ray, Intersection& intersection) const override;
  bool occluded(const Ray& ray) const override;
  std::string_view name() const override { return "embree"; }
  AcceleratorReport report() const override;

  Mode mode() const;

  struct State;

 private:
  std::unique_ptr<State> state_;
};

}  // namespace candela
