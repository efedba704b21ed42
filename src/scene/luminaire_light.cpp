#include "scene/luminaire_light.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "math/constants.h"
#include "shading/photometric_units.h"

namespace candela {

LuminaireLight::LuminaireLight(std::shared_ptr<const Photometry> photometry, const Vec3& position,
                               const Vec3& nadir, const Vec3& c0, double scale, const Color& colour,
                               double width, double depth, int samples)
    : photometry_(std::move(photometry)), position_(position), scale_(scale) {
  if (!(length(nadir) > 0)) throw std::invalid_argument("the nadir direction must be non-zero");
  nadir_ = normalize(nadir);
  const Vec3 across = c0 - nadir_ * dot(c0, nadir_);
  if (!(length(across) > 1e-9 * length(c0)))
    throw std::invalid_argument("c0 must not be parallel to the nadir");
  c0_ = normalize(across);
  // C grows counter-clockwise seen from above, looking along the nadir (LM-63's type C): with
  // the nadir −y and C0 along +x, C90 is −z, c0 × nadir.
  c90_ = cross(c0_, nadir_);
  per_candela_ = radiometric(1, colour);
  flux_ = photometry_->flux() * scale_;
  if (!(width >= 0 && depth >= 0)) throw std::invalid_argument("a luminaire's size must not be negative");
  across_c0_ = c0_ * width;
  across_c90_ = c90_ * depth;
  area_ = width > 0 || depth > 0;
  samples_ = area_ ? std::max(1, samples) : 1;
}

double LuminaireLight::candela_toward(const Vec3& direction) const {
  const double cos_gamma = std::clamp(dot(direction, nadir_), -1.0, 1.0);
  const double gamma = std::acos(cos_gamma) * 180 / kPi;
  double c = std::atan2(dot(direction, c90_), dot(direction, c0_)) * 180 / kPi;
  if (c < 0) c += 360;
  return scale_ * photometry_->intensity(gamma, c);
}

bool LuminaireLight::illuminate(const Vec3& point, LightSample& sample) const {
  return illuminate_from({0.5, 0.5}, point, 1, sample);
}

bool LuminaireLight::illuminate_sample(const Vec3& point, int index, const Vec2& within,
                                       LightSample& sample) const {
  if (!area_) return index == 0 && illuminate(point, sample);
  return illuminate_from(stratum_point(index, samples_, within), point, 1.0 / (samples_ * samples_), sample);
}

bool LuminaireLight::illuminate_random(const Vec3& point, const Vec2& u, LightSample& sample) const {
  return illuminate_from(area_ ? u : Vec2{0.5, 0.5}, point, 1, sample);
}

bool LuminaireLight::illuminate_from(const Vec2& u, const Vec3& point, double share,
                                     LightSample& sample) const {
  sample = {};
  const Vec3 from_light = point - (position_ + across_c0_ * (u.x - 0.5) + across_c90_ * (u.y - 0.5));
  const double distance = length(from_light);
  if (!(distance > 0)) return false;
  const double candela = candela_toward(from_light / distance);
  if (!(candela > 0)) return false;
  sample.distance = distance;
  sample.direction = -from_light / distance;
  sample.intensity = per_candela_ * (share * candela / (distance * distance));
  return true;
}

Color LuminaireLight::power(double) const {
  return per_candela_ * flux_;
}

}  // namespace candela
