#include "scene/environment_light.h"

#include <cmath>
#include <stdexcept>

#include "math/constants.h"
#include "sampling/sphere_quadrature.h"

namespace candela {

EnvironmentLight::EnvironmentLight(const Environment& environment, int samples)
    : environment_(environment), samples_(samples) {
  if (samples < 1) throw std::invalid_argument("environment light: samples must be >= 1");
  // The mean over the sphere on a grid finer than a texel of the maps used in practice (exact for
  // a constant sky).
  mean_radiance_ = integrate_over_sphere(
                       [&](const Vec3& direction) { return environment_.radiance(direction); }, 128, 256) /
                   (4 * kPi);
}

bool EnvironmentLight::from(const Vec2& u, int cells, LightSample& sample) const {
  sample = {};
  Vec3 direction;
  double pdf = 0;
  Color radiance;
  if (!environment_.sample(u, direction, pdf, radiance) || !(pdf > 0)) return false;
  sample.direction = direction;
  sample.distance = kInfinity;
  sample.intensity = radiance * (kInvPi / (cells * pdf));
  sample.pdf = pdf;
  return std::isfinite(sample.intensity.r + sample.intensity.g + sample.intensity.b);
}

bool EnvironmentLight::illuminate(const Vec3&, LightSample& sample) const {
  return from({0.5, 0.5}, 1, sample);
}

bool EnvironmentLight::illuminate_sample(const Vec3&, int index, const Vec2& within,
                                         LightSample& sample) const {
  if (index < 0 || index >= samples_ * samples_) return false;
  return from(stratum_point(index, samples_, within), samples_ * samples_, sample);
}

bool EnvironmentLight::illuminate_random(const Vec3&, const Vec2& u, LightSample& sample) const {
  return from(u, 1, sample);
}

}  // namespace candela
