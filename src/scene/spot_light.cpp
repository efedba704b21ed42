#include "scene/spot_light.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "math/constants.h"
#include "math/direction.h"

namespace candela {

SpotLight::SpotLight(const Vec3& position, const Vec3& target, const Color& intensity, double cutoff_degrees,
                     double falloff_start_degrees, double exponent, const Attenuation& attenuation)
    : position_(position),
      intensity_(intensity),
      cos_cutoff_(std::cos(degrees_to_radians(cutoff_degrees))),
      cos_falloff_start_(std::cos(degrees_to_radians(falloff_start_degrees))),
      exponent_(exponent),
      attenuation_(attenuation) {
  const Vec3 axis = target - position;
  const std::optional<Vec3> unit = direction_of(axis);
  if (!unit) throw std::invalid_argument("target must differ from position");
  axis_ = *unit;
}

double SpotLight::cone_factor(double cos_alpha) const {
  if (cos_alpha <= cos_cutoff_) return 0;
  double factor = exponent_ > 0 ? std::pow(cos_alpha, exponent_) : 1.0;
  if (cos_alpha < cos_falloff_start_) {
    const double x = (cos_alpha - cos_cutoff_) / (cos_falloff_start_ - cos_cutoff_);
    factor *= x * x * (3 - 2 * x);
  }
  return factor;
}

double SpotLight::solid_angle() const {
  // dω = 2π d(cos α): the cone is cos α in (cos_cutoff, 1].
  constexpr int kSteps = 4096;
  const double width = (1 - cos_cutoff_) / kSteps;
  double sum = 0;
  for (int i = 0; i < kSteps; ++i) sum += cone_factor(cos_cutoff_ + (i + 0.5) * width);
  return 2 * kPi * sum * width;
}

Color SpotLight::power(double scene_radius) const {
  const double cone = 0.5 * (1 - 0.5 * (cos_cutoff_ + cos_falloff_start_));
  return intensity_ * (cone * attenuation_.factor(scene_radius) * 4 * kPi * scene_radius * scene_radius);
}

bool SpotLight::illuminate(const Vec3& point, LightSample& sample) const {
  sample = {};
  const Vec3 to_light = position_ - point;
  sample.distance = length(to_light);
  if (!(sample.distance > 0)) return false;
  sample.direction = to_light / sample.distance;
  const double factor = cone_factor(dot(-sample.direction, axis_));
  if (factor <= 0) return false;
  sample.intensity = intensity_ * (factor * attenuation_.factor(sample.distance));
  return true;
}

}  // namespace candela
