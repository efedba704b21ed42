// Methods that compute a radiance per camera ray: tiles rendered in parallel (TBB), the rays
// where the scene's aa settings put them (camera/antialiasing.h: every mode and filter), a
// per-pixel random stream so images do not depend on the thread count (SPEC §6).
#pragma once

#include <memory>

#include "integrators/method.h"
#include "integrators/ray_tree.h"
#include "math/pcg32.h"

namespace candela {

struct TraceContext {
  RayCounts counts;
  Pcg32 rng;
  RayTree* tree = nullptr;  // set only when a pixel's ray tree is being printed
  // The render's seed (RenderRequest::seed_for), which jitters the lights' samples
  // (local_illumination), so that a render with its own seed leaves the scene's alone.
  uint64_t seed = 0;
};

class RayTracingMethod : public Method {
 public:
  RenderResult render(const Scene& scene, const RenderRequest& request) const override;
  // The radiance along a primary ray, recording the ray tree when context.tree is set.
  virtual Color trace_primary(const Scene& scene, const Ray& ray, TraceContext& context) const = 0;
  // Traces pixel (x, y) alone and returns its ray tree.
  RayTree pixel_ray_tree(const Scene& scene, int x, int y, Color& radiance) const override;
};

}  // namespace candela
