#include "scene/environment_light.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "math/constants.h"

namespace candela {

EnvironmentLight::EnvironmentLight(const Environment& environment, int samples)
    : environment_(environment), samples_(samples) {
  if (samples < 1) throw std::invalid_argument("environment light: samples must be >= 1");
  // The mean over the sphere by the midpoint rule in (cos θ, φ) — cells of equal solid angle — on
  // a grid finer than a texel of the maps used in practice (exact for a constant sky).
  constexpr int kBands = 128, kSectors = 256;
  Color sum;
  for (int band = 0; band < kBands; ++band) {
    const double z = 1 - 2 * (band + 0.5) / kBands;
    const double ring = std::sqrt(std::max(0.0, 1 - z * z));
    for (int sector = 0; sector < kSectors; ++sector) {
      const double phi = 2 * kPi * (sector + 0.5) / kSectors;
      sum += environment_.radiance({ring * std::cos(phi), z, ring * std::sin(phi)});
    }
  }
  mean_radiance_ = sum / double(kBands * kSectors);
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
