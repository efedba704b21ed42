#include "integrators/local.h"

#include "integrators/whitted.h"

namespace candela {

Color LocalMethod::trace_primary(const Scene& scene, const Ray& ray, TraceContext& context) const {
  // Ray casting is the ray tree cut at depth 0.
  return trace_ray_tree(scene, ray, {0, 1.0, scene.local.shadows}, context);
}

}  // namespace candela
