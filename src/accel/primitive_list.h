#pragma once

#include "accel/accelerator.h"

namespace candela {

// The brute-force baseline: every ray against every primitive (SPEC §5, 001 "O(n)").
class PrimitiveList final : public Accelerator {
 public:
  void build(std::span<const Primitive> primitives) override { primitives_ = primitives; }
  bool intersect(const Ray& ray, Intersection& intersection) const override;
  bool occluded(const Ray& ray) const override;
  std::string_view name() const override { return "list"; }

 private:
  std::span<const Primitive> primitives_;
};

}  // namespace candela
