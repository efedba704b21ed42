#include "integrators/light_sampler.h"

#include <algorithm>
#include <cmath>

#include "scene/surface_emitter_index.h"

namespace candela {

LightSampler::LightSampler(const Scene& scene) : scene_(scene) {
  const Bounds3& bounds = scene.bounds();
  double radius = bounds.empty() || !bounds.is_finite() ? 0.0 : 0.5 * length(bounds.diagonal());
  if (!(radius > 0)) radius = 1;  // planes alone: any common scale will do
  const std::size_t count = scene.emitter_count();
  std::vector<double> power(count, 0.0);
  double total = 0;
  for (std::size_t i = 0; i < count; ++i) {
    const double weight = luminance(scene.emitter(i).power(radius));
    if (!(weight > 0) || !std::isfinite(weight)) continue;
    power[i] = weight;
    total += weight;
  }
  probability_.assign(count, 0.0);
  if (!(total > 0)) return;
  double running = 0;
  for (std::size_t i = 0; i < count; ++i) {
    if (power[i] == 0) continue;
    probability_[i] = power[i] / total;
    running += probability_[i];
    chosen_.push_back(i);
    cumulative_.push_back(running);
  }
  cumulative_.back() = 1;

  // A BSDF ray that hits an emissive primitive is weighed by the chance that next-event
  // estimation picks that primitive: its object's probability times its share of the area.
  const SurfaceEmitterIndex emitters(scene);
  if (!emitters.empty())
    for (uint32_t p = 0; p < scene.primitives.size(); ++p) {
      const uint32_t light = emitters.light_of(p);
      if (light == SurfaceEmitterIndex::kNone) continue;
      const double chosen = probability_[scene.lights.size() + light];
      if (chosen == 0) continue;
      if (primitive_choice_.empty()) primitive_choice_.assign(scene.primitives.size(), 0.0);
      primitive_choice_[p] = chosen * emitters.share_of(p);
      ++emissive_primitives_;
    }
  if (scene.environment_light && scene.environment) {
    environment_ = scene.environment.get();
    environment_probability_ = probability_[count - 1];
  }
}

LightSampler::Choice LightSampler::choose(double u) const {
  const auto found = std::upper_bound(cumulative_.begin(), cumulative_.end(), u);
  const std::size_t i = std::min<std::size_t>(found - cumulative_.begin(), chosen_.size() - 1);
  return {chosen_[i], probability_[chosen_[i]]};
}

double LightSampler::surface_pdf(uint32_t primitive, const Vec3& from, const SurfaceHit& at) const {
  if (primitive >= primitive_choice_.size() || primitive_choice_[primitive] == 0) return 0;
  return primitive_choice_[primitive] * scene_.primitives[primitive].shape->pdf_from(from, at);
}

double LightSampler::environment_pdf(const Vec3& direction) const {
  return environment_ ? environment_probability_ * environment_->pdf(direction) : 0.0;
}

}  // namespace candela
