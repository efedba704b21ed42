#include "integrators/light_sampler.h"

#include <algorithm>

namespace candela {

LightSampler::LightSampler(const Scene& scene) : scene_(scene) {
  double total = 0;
  std::vector<double> power;
  for (uint32_t p = 0; p < scene.primitives.size(); ++p) {
    const Primitive& primitive = scene.primitives[p];
    const Color& emission = scene.materials[primitive.material].emission;
    if (emission.is_black()) continue;
    const double area = primitive.shape->area();
    const double weight = luminance(emission) * area;
    if (!(weight > 0) || !std::isfinite(weight)) continue;
    surfaces_.push_back(p);
    power.push_back(weight);
    total += weight;
  }
  if (!surfaces_.empty()) {
    surface_probability_.assign(scene.primitives.size(), 0.0);
    double running = 0;
    for (std::size_t i = 0; i < surfaces_.size(); ++i) {
      running += power[i];
      surface_cdf_.push_back(running / total);
    }
    surface_cdf_.back() = 1;
  }
  // The background lights nothing (issue 19): a sky is an environment ({"type": "constant"}).
  if (scene.environment) environment_ = scene.environment.get();
  choice_count_ =
      static_cast<int>(scene.lights.size()) + (surfaces_.empty() ? 0 : 1) + (environment_ ? 1 : 0);
  if (!surfaces_.empty()) {
    const double group = 1.0 / choice_count_;
    double previous = 0;
    for (std::size_t i = 0; i < surfaces_.size(); ++i) {
      surface_probability_[surfaces_[i]] = group * (surface_cdf_[i] - previous);
      previous = surface_cdf_[i];
    }
  }
}

LightSampler::Choice LightSampler::choose(double u) const {
  const double scaled = u * choice_count_;
  const int slot = std::min(static_cast<int>(scaled), choice_count_ - 1);
  const int light_count = static_cast<int>(scene_.lights.size());
  if (slot < light_count) return {Kind::scene_light, static_cast<uint32_t>(slot), 1.0 / choice_count_};
  if (slot == light_count && !surfaces_.empty()) {
    // The rest of u picks the primitive: it is uniform in [0, 1) again.
    const double v = std::clamp(scaled - slot, 0.0, 1.0);
    const auto found = std::upper_bound(surface_cdf_.begin(), surface_cdf_.end(), v);
    const std::size_t i = std::min<std::size_t>(found - surface_cdf_.begin(), surfaces_.size() - 1);
    return {Kind::surface, surfaces_[i], surface_probability_[surfaces_[i]]};
  }
  return {Kind::environment, 0, 1.0 / choice_count_};
}

double LightSampler::surface_probability(uint32_t primitive) const {
  return primitive < surface_probability_.size() ? surface_probability_[primitive] : 0.0;
}

}  // namespace candela
