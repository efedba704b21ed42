#pragma once

#include <vector>

#include "accel/accelerator.h"
#include "accel/bounding_volume.h"

namespace candela {

// The brute-force baseline: every ray against every primitive (SPEC §5, 001 "O(n)"),
// optionally testing each scene object's bounding volume first (000 §5.7.1). Only the
// reportable primitives (reportable_primitives) are tested, in index order.
class PrimitiveList final : public Accelerator {
 public:
  explicit PrimitiveList(BoundingVolumeKind bounding_volume = BoundingVolumeKind::none)
      : bounding_volume_(bounding_volume) {}
  void build(std::span<const Primitive> primitives) override;
  bool intersect(const Ray& ray, Intersection& intersection) const override;
  bool occluded(const Ray& ray) const override;
  std::string_view name() const override { return "list"; }
  AcceleratorReport report() const override;

 private:
  // A run of tested_ of one object behind one bounding volume.
  struct Group {
    uint32_t first, count;  // positions in tested_
    ObjectBound bound;
  };
  BoundingVolumeKind bounding_volume_;
  std::span<const Primitive> primitives_;
  std::vector<uint32_t> tested_;  // the reportable primitives, ascending
  std::vector<Group> groups_;     // empty without bounding volumes
};

}  // namespace candela
