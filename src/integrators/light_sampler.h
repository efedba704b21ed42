// Which light a path vertex samples for next-event estimation (SPEC §12), and with what
// probability, so that a BSDF-sampled ray that happens to hit an emitter can weigh itself
// against it (multiple importance sampling).
//
// The choices: each scene light (point, spot, directional, area), the emissive surfaces as one
// group, and the environment (a map or a constant sky; the background color lights nothing) — each
// with the same probability; inside the group, an emissive primitive by its power
// (luminance of E × area). Emissive primitives whose shape cannot be sampled (the plane) are
// left to BSDF sampling alone.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "scene/scene.h"
#include "shading/environment.h"

namespace candela {

class LightSampler {
 public:
  explicit LightSampler(const Scene& scene);

  enum class Kind { scene_light, surface, environment };
  struct Choice {
    Kind kind = Kind::scene_light;
    uint32_t index = 0;      // scene light index, or primitive index
    double probability = 0;  // of this choice
  };

  bool empty() const { return choice_count_ == 0; }
  // A choice with u uniform in [0, 1).
  Choice choose(double u) const;
  // The probability that choose() picks primitive (0 when it is not a sampled emitter).
  double surface_probability(uint32_t primitive) const;
  double environment_probability() const { return environment_ ? 1.0 / choice_count_ : 0.0; }
  // The environment that next-event estimation samples, or null when nothing arrives from outside.
  const Environment* environment() const { return environment_; }
  std::size_t emissive_primitive_count() const { return surfaces_.size(); }

 private:
  const Scene& scene_;
  int choice_count_ = 0;
  std::vector<uint32_t> surfaces_;           // emissive, sampleable primitives
  std::vector<double> surface_cdf_;          // running power fractions, last = 1
  std::vector<double> surface_probability_;  // per primitive of the scene (empty without emitters)
  const Environment* environment_ = nullptr;
};

}  // namespace candela
