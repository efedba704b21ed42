#include "scene/direct_irradiance.h"

#include <cmath>

#include "math/constants.h"
#include "sampling/multiple_importance.h"
#include "sampling/warps.h"
#include "scene/light_samples.h"
#include "scene/scene.h"
#include "scene/surface_emitter_index.h"

namespace candela {

Color direct_irradiance(const Scene& scene, const Vec3& point, const Vec3& normal, EmitterSet emitters,
                        const StratumJitter& jitter, const HemisphereRays* hemisphere) {
  Color sum;
  const double offset = scene.ray_offset(point);
  const Vec3 origin = point + normal * offset;
  // With hemisphere rays, N cos θ/π is their density toward a direction (all N of them).
  const bool weighed = hemisphere && hemisphere->rays > 0 && !hemisphere->emitters.empty() &&
                       emitters == EmitterSet::everything;
  const double ray_count = weighed ? hemisphere->rays : 0;
  for (std::size_t e = 0; e < scene.emitter_count(); ++e) {
    const bool surface = scene.is_surface_emitter(e);
    if (emitters != EmitterSet::everything && surface) continue;
    if (emitters == EmitterSet::lights && e >= scene.lights.size()) break;
    const Light& light = scene.emitter(e);
    const double sample_count = light.sample_count();
    for_each_light_sample(light, e, point, offset, jitter, [&](const LightSample& sample, double reach) {
      const double cosine = dot(normal, sample.direction);
      if (!(cosine > 0) || !(reach > 0)) return;
      const Color through = scene.transmittance({origin, sample.direction, 0.0, reach});  // window panes
      if (through.is_black()) return;
      const double weight =
          weighed && surface ? power_heuristic(sample_count * sample.pdf, ray_count * cosine * kInvPi) : 1.0;
      sum += sample.intensity * through * (cosine * weight);
    });
  }
  if (!weighed) return sum;
  Vec3 b1, b2;
  orthonormal_basis(normal, b1, b2);
  for (int r = 0; r < hemisphere->rays; ++r) {
    const Vec3 local =
        square_to_cosine_hemisphere({hemisphere->random.next_double(), hemisphere->random.next_double()});
    Ray ray;
    ray.origin = origin;
    ray.direction = normalize(b1 * local.x + b2 * local.y + normal * local.z);
    Intersection hit;
    Color through;
    if (!scene.intersect_past_sheets(ray, hit, through) || through.is_black()) continue;
    const uint32_t light = hemisphere->emitters.light_of(hit.primitive);
    if (light == SurfaceEmitterIndex::kNone) continue;
    const Light& emitter = *scene.surface_lights[light];
    const double light_pdf = hemisphere->emitters.pdf(hit.primitive, point, hit.surface);
    const double cosine = local.z;
    // L cos θ / (N cos θ/π) with L = E/π: E/N, weighed against the light's samples.
    const double weight = power_heuristic(ray_count * cosine * kInvPi, emitter.sample_count() * light_pdf);
    sum += emitter.emitted_radiance(ray.direction) * through * (weight / ray_count);
  }
  return sum;
}

}  // namespace candela
