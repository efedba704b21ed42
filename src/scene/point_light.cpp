#include "scene/point_light.h"

namespace candela {

bool PointLight::illuminate(const Vec3& point, LightSample& sample) const {
  sample = {};
  const Vec3 to_light = position_ - point;
  sample.distance = length(to_light);
  if (!(sample.distance > 0)) return false;
  sample.direction = to_light / sample.distance;
  sample.intensity = intensity_ * attenuation_.factor(sample.distance);
  return true;
}

}  // namespace candela
