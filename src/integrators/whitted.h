// Whitted ray tracing (000 §5.1–5.5, 001; SPEC §8).
//
// I = local + kr·I_r + kt·I_t with R = 2N(N·V) − V and the refraction vector of 000 eq. 5-7;
// total internal reflection sends the transmitted share along the internal mirror direction.
// The ray tree ends on a miss (background), at whitted.max_depth (primary rays are depth 0,
// so depth 0 is ray casting), or adaptively when the product of the k's along the path falls
// below whitted.min_weight (000 §5.5).
//
// Settings: whitted.max_depth (5), whitted.min_weight (0.001), whitted.shadows (true).
#pragma once

#include "integrators/ray_tracing_method.h"
#include "io/json_node.h"

namespace candela {

// The scene file's "whitted" object.
struct WhittedSettings {
  int max_depth = 5;         // primary rays are depth 0 (000 §5.5)
  double min_weight = 1e-3;  // adaptive depth: stop when the product of the k's is below
  bool shadows = true;
};
WhittedSettings read_whitted_settings(const JsonNode& node);

// Where the recursion stops and whether shadow rays are cast.
struct TreeLimits {
  int max_depth = 5;
  double min_weight = 1e-3;
  bool shadows = true;
  // The see-through blend of 000 §4.4 may go deeper than reflection and refraction: it is part
  // of the local model (a surface seen through another), so ray casting keeps it.
  int see_through_depth = 5;
};

// The radiance along a primary ray by the recursion above; with max_depth 0 it is ray
// casting with the local model (the local method).
Color trace_ray_tree(const Scene& scene, const Ray& ray, const TreeLimits& limits, TraceContext& context);

class WhittedMethod final : public RayTracingMethod {
 public:
  explicit WhittedMethod(const WhittedSettings& settings = {}) : settings_(settings) {}
  std::string_view name() const override { return "whitted"; }
  Color trace_primary(const Scene& scene, const Ray& ray, TraceContext& context) const override {
    return trace_ray_tree(scene, ray,
                          {settings_.max_depth, settings_.min_weight, settings_.shadows, settings_.max_depth},
                          context);
  }

 private:
  WhittedSettings settings_;
};

}  // namespace candela
