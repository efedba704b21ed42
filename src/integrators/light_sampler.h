// Which emitter a path vertex samples for next-event estimation (SPEC §12), and with what
// probability, so that a BSDF-sampled ray that happens to hit an emitter can weigh itself
// against it (multiple importance sampling).
//
// The choices are the scene's emitters as the one Light interface gives them (Scene::emitter:
// the scene lights, the emissive objects, the environment; the background lights nothing), each
// with probability proportional to its power (pbrt's PowerLightSampler; Light::power, the scene's
// bounding radius for the lights without a finite power); an emissive object then picks one of
// its primitives by area (SurfaceLight). Emissive primitives whose shape cannot be sampled (the
// plane) are left to BSDF sampling alone.
#pragma once

#include <cstdint>
#include <vector>

#include "scene/scene.h"
#include "shading/environment.h"

namespace candela {

class LightSampler {
 public:
  explicit LightSampler(const Scene& scene);

  struct Choice {
    std::size_t emitter = 0;  // Scene::emitter index
    double probability = 0;   // of this choice
  };

  bool empty() const { return cumulative_.empty(); }
  // A choice with u uniform in [0, 1).
  Choice choose(double u) const;
  // Whether there is only one emitter to choose (choose needs no random value).
  bool single() const { return cumulative_.size() == 1; }
  double probability(std::size_t emitter) const {
    return emitter < probability_.size() ? probability_[emitter] : 0.0;
  }
  // The density with which next-event estimation draws the direction from `from` toward `at` on
  // primitive `primitive` (0 when the primitive is not part of a sampled emitter).
  double surface_pdf(uint32_t primitive, const Vec3& from, const SurfaceHit& at) const;
  // The density with which it draws the direction toward the environment (0 without one).
  double environment_pdf(const Vec3& direction) const;
  bool has_environment() const { return environment_ != nullptr; }
  std::size_t emissive_primitive_count() const { return emissive_primitives_; }

 private:
  const Scene& scene_;
  std::vector<double> probability_;       // per emitter
  std::vector<double> cumulative_;        // running probabilities of the emitters chosen, last = 1
  std::vector<std::size_t> chosen_;       // the emitters with power > 0, in emitter order
  std::vector<double> primitive_choice_;  // per primitive: P(its emitter) · P(it | the emitter)
  std::size_t emissive_primitives_ = 0;
  const Environment* environment_ = nullptr;
  double environment_probability_ = 0;
};

}  // namespace candela
