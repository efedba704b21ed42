#include "integrators/local.h"

#include "integrators/probe.h"
#include "integrators/whitted.h"

namespace candela {

LocalSettings read_local_settings(const JsonNode& node) {
  LocalSettings settings;
  node.expect_object();
  settings.shadows = node.boolean("shadows", settings.shadows);
  node.finish();
  return settings;
}

// The direct light at the sensor, every emitter's samples with opaque shadows (probe.h).
std::unique_ptr<PointProbe> LocalMethod::point_probe(const Scene& scene,
                                                     const ProbeSettings& settings) const {
  return make_local_probe(scene, settings);
}

Color LocalMethod::trace_primary(const Scene& scene, const Ray& ray, TraceContext& context) const {
  // Ray casting is the ray tree cut at depth 0, but for the see-through blend of 000 §4.4 (a
  // local-model effect): up to kSeeThroughDepth transparent surfaces one behind the other.
  constexpr int kSeeThroughDepth = 16;
  return trace_ray_tree(scene, ray, {0, 1e-3, settings_.shadows, kSeeThroughDepth}, context);
}

}  // namespace candela
