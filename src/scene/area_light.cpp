#include "scene/area_light.h"

#include <cmath>
#include <stdexcept>

#include "math/constants.h"

namespace candela {

AreaLight::AreaLight(const Vec3& corner, const Vec3& edge_u, const Vec3& edge_v, const Color& exitance,
                     int samples, bool two_sided)
    : corner_(corner),
      edge_u_(edge_u),
      edge_v_(edge_v),
      exitance_(exitance),
      samples_(samples),
      two_sided_(two_sided) {
  const Vec3 face = cross(edge_u, edge_v);
  area_ = length(face);
  if (!(area_ > 0) || !std::isfinite(area_))
    throw std::invalid_argument("area light: the edges must span an area");
  if (samples < 1) throw std::invalid_argument("area light: samples must be >= 1");
  normal_ = face / area_;
}

bool AreaLight::from(const Vec3& point, const Vec3& y, double patch_area, LightSample& sample) const {
  sample = {};
  const Vec3 to_light = y - point;
  const double d2 = dot(to_light, to_light);
  if (!(d2 > 0)) return false;
  const double d = std::sqrt(d2);
  sample.direction = to_light / d;
  sample.distance = d;
  // cos θ_l at the light: toward the point, from the front (or either side).
  double cosine = -dot(normal_, sample.direction);
  if (two_sided_) cosine = std::fabs(cosine);
  if (!(cosine > 0)) return false;
  sample.intensity = exitance_ * (kInvPi * cosine * patch_area / d2);
  return true;
}

bool AreaLight::illuminate(const Vec3& point, LightSample& sample) const {
  return from(point, corner_ + (edge_u_ + edge_v_) * 0.5, area_, sample);
}

bool AreaLight::illuminate_sample(const Vec3& point, int index, const Vec2& within,
                                  LightSample& sample) const {
  if (index < 0 || index >= samples_ * samples_) return false;
  const auto [s, t] = stratum_point(index, samples_, within);
  return from(point, corner_ + edge_u_ * s + edge_v_ * t, area_ / (samples_ * samples_), sample);
}

bool AreaLight::illuminate_random(const Vec3& point, const Vec2& u, LightSample& sample) const {
  return from(point, corner_ + edge_u_ * u.x + edge_v_ * u.y, area_, sample);
}

}  // namespace candela
