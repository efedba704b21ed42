// Ray casting with the local model only (001 "Ray-casting"; 000 §2): the nearest surface
// along each primary ray, shaded by ambient plus every light, no secondary rays.
//
// Settings: local.shadows (true): shadow rays toward each light, as 001's s factor.
#pragma once

#include "integrators/ray_tracing_method.h"
#include "io/json_node.h"

namespace candela {

// The scene file's "local" object.
struct LocalSettings {
  bool shadows = true;
};
LocalSettings read_local_settings(const JsonNode& node);

class LocalMethod final : public RayTracingMethod {
 public:
  explicit LocalMethod(const LocalSettings& settings = {}) : settings_(settings) {}
  std::string_view name() const override { return "local"; }
  Color trace_primary(const Scene& scene, const Ray& ray, TraceContext& context) const override;
  std::unique_ptr<PointProbe> point_probe(const Scene& scene, const ProbeSettings& settings) const override;

 private:
  LocalSettings settings_;
};

}  // namespace candela
