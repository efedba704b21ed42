#include "scene/direct_irradiance.h"

#include <cmath>

#include "scene/scene.h"

namespace candela {

Color direct_irradiance(const Scene& scene, const Vec3& point, const Vec3& normal, EmitterSet emitters,
                        const StratumJitter& jitter) {
  Color sum;
  const double offset = scene.ray_offset(point);
  const Vec3 origin = point + normal * offset;
  for (std::size_t e = 0; e < scene.emitter_count(); ++e) {
    if (emitters != EmitterSet::everything && scene.is_surface_emitter(e)) continue;
    if (emitters == EmitterSet::lights && e >= scene.lights.size()) break;
    const Light& light = scene.emitter(e);
    for (int index = 0; index < light.sample_count(); ++index) {  // an area light's samples²
      LightSample sample;
      if (!light.illuminate_sample(point, index, jitter.at(point, e, index), sample)) continue;
      const double cosine = dot(normal, sample.direction);
      if (!(cosine > 0)) continue;
      Ray shadow;
      shadow.origin = origin;
      shadow.direction = sample.direction;
      // Short of the light by the offset at both ends, as the local model: an emissive quad drawn
      // where an area light is must not shadow it, nor an emissive surface itself.
      shadow.t_max = std::isinf(sample.distance) ? kInfinity : sample.distance - 2 * offset;
      if (!(shadow.t_max > 0)) continue;
      if (scene.occluded(shadow)) continue;
      sum += sample.intensity * cosine;
    }
  }
  return sum;
}

}  // namespace candela
