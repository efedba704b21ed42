#include "scene/surface_light.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "math/constants.h"

namespace candela {

SurfaceLight::SurfaceLight(std::string object_name, const std::vector<const Shape*>& shapes,
                           const Color& emission, int samples)
    : object_name_(std::move(object_name)), emission_(emission), samples_(samples) {
  if (samples < 1) throw std::invalid_argument("surface light: samples must be >= 1");
  for (const Shape* shape : shapes) {
    const double area = shape->area();
    if (!(area > 0) || !std::isfinite(area)) continue;
    area_ += area;
    shapes_.push_back(shape);
    cumulative_area_.push_back(area_);
  }
  if (shapes_.empty()) throw std::invalid_argument("surface light: no shape of the object can be sampled");
}

bool SurfaceLight::from(const Vec3& point, Vec2 u, int cells, LightSample& sample) const {
  sample = {};
  // u.x picks a shape by its area, then is stretched back over [0, 1) within it.
  const double at = u.x * area_;
  const auto found = std::upper_bound(cumulative_area_.begin(), cumulative_area_.end(), at);
  const std::size_t i = std::min<std::size_t>(found - cumulative_area_.begin(), shapes_.size() - 1);
  const double before = i == 0 ? 0.0 : cumulative_area_[i - 1];
  const double shape_area = cumulative_area_[i] - before;
  const double probability = shape_area / area_;
  u.x = std::clamp((at - before) / shape_area, 0.0, std::nextafter(1.0, 0.0));
  SurfaceSample on_surface;
  if (!shapes_[i]->sample_from(point, u, on_surface) || !(on_surface.pdf > 0)) return false;
  const Vec3 to_light = on_surface.position - point;
  const double distance = length(to_light);
  if (!(distance > 0)) return false;
  sample.direction = to_light / distance;
  sample.distance = distance;
  sample.intensity = emission_ * (kInvPi / (cells * probability * on_surface.pdf));
  sample.pdf = probability * on_surface.pdf;
  sample.normal = on_surface.normal;
  return std::isfinite(sample.intensity.r + sample.intensity.g + sample.intensity.b);
}

bool SurfaceLight::illuminate(const Vec3& point, LightSample& sample) const {
  return from(point, {0.5, 0.5}, 1, sample);
}

bool SurfaceLight::illuminate_sample(const Vec3& point, int index, const Vec2& within,
                                     LightSample& sample) const {
  if (index < 0 || index >= samples_ * samples_) return false;
  return from(point, stratum_point(index, samples_, within), samples_ * samples_, sample);
}

bool SurfaceLight::illuminate_random(const Vec3& point, const Vec2& u, LightSample& sample) const {
  return from(point, u, 1, sample);
}

}  // namespace candela
