// Which surface light (Scene::surface_lights) samples each emissive primitive, and the primitive's
// share of that light's area — the chance that the light's one random sample lands on it
// (SurfaceLight picks a shape by area). What weighs a ray that hits an emissive surface against
// the light's own sampling (multiple importance sampling, Veach 1997 ch. 9): the path tracer's
// next-event estimation and meshless η (scene/direct_irradiance.h).
#pragma once

#include <cstdint>
#include <limits>
#include <vector>

#include "geometry/shape.h"

namespace candela {

class Scene;

class SurfaceEmitterIndex {
 public:
  static constexpr uint32_t kNone = std::numeric_limits<uint32_t>::max();

  // Empty (nothing costs memory) when the scene has no surface lights; otherwise one entry per
  // primitive, a mesh's millions too.
  explicit SurfaceEmitterIndex(const Scene& scene);

  bool empty() const { return light_.empty(); }
  // The surface light that samples the primitive, or kNone.
  uint32_t light_of(uint32_t primitive) const {
    return primitive < light_.size() ? light_[primitive] : kNone;
  }
  // The primitive's share of its light's area (0 for kNone).
  double share_of(uint32_t primitive) const { return primitive < share_.size() ? share_[primitive] : 0.0; }
  // The solid-angle density with which its light's one random sample (SurfaceLight::illuminate_random)
  // finds the point `at` of the primitive from `from`: share × Shape::pdf_from. 0 for kNone.
  double pdf(uint32_t primitive, const Vec3& from, const SurfaceHit& at) const;

 private:
  const Scene& scene_;
  std::vector<uint32_t> light_;
  std::vector<double> share_;
};

}  // namespace candela
