#include "integrators/local.h"

#include "integrators/whitted.h"

namespace candela {

Color LocalMethod::trace_primary(const Scene& scene, const Ray& ray, TraceContext& context) const {
  // Ray casting is the ray tree cut at depth 0, but for the see-through blend of 000 §4.4 (a
  // local-model effect): up to kSeeThroughDepth transparent surfaces one behind the other.
  constexpr int kSeeThroughDepth = 16;
  return trace_ray_tree(scene, ray, {0, 1e-3, scene.local.shadows, kSeeThroughDepth}, context);
}

}  // namespace candela
