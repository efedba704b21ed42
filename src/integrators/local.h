// Ray casting with the local model only (001 "Ray-casting"; 000 §2): the nearest surface
// along each primary ray, shaded by ambient plus every light, no secondary rays.
//
// Settings: local.shadows (true): shadow rays toward each light, as 001's s factor.
#pragma once

#include "integrators/ray_tracing_method.h"

namespace candela {

class LocalMethod final : public RayTracingMethod {
 public:
  std::string_view name() const override { return "local"; }
  Color trace_primary(const Scene& scene, const Ray& ray, TraceContext& context) const override;
};

}  // namespace candela
