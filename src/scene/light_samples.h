// The one loop over a light's samples that a shaded point takes (SPEC §8; 000 §2, 001's I_lum):
// one sample for a point-like light, n × n for an area light, an emissive surface or the
// environment, each jittered within its cell per shading point (StratumJitter: soft shadows
// without stepped penumbrae), each with the reach of its shadow ray. The local model's shading
// (integrators/direct_lighting.h), the rasterizer's dot-product shadows and direct_irradiance (the
// meshless η, the radiosity first shot's lights, probe's local answer) all walk it; each tests
// the shadow its own way (a ray tree and absorption, or window panes).
#pragma once

#include <cmath>
#include <cstddef>

#include "math/constants.h"
#include "scene/light.h"

namespace candela {

// The reach of a shadow ray from a point lifted `offset` off its surface toward a light sample:
// short of the sample by the offset at both ends — an emissive quad drawn where an area light is
// must not shadow it, nor an emissive surface itself — and unbounded toward a light at infinity.
inline double shadow_reach(const LightSample& sample, double offset) {
  return std::isfinite(sample.distance) ? sample.distance - 2 * offset : kInfinity;
}

// Calls visit(sample, reach) for each sample of emitter `light_index` that illuminates `point`.
template <typename Visit>
void for_each_light_sample(const Light& light, std::size_t light_index, const Vec3& point, double offset,
                           const StratumJitter& jitter, Visit&& visit) {
  for (int index = 0; index < light.sample_count(); ++index) {
    LightSample sample;
    if (illuminate_cell(light, point, light_index, index, jitter, sample))
      visit(sample, shadow_reach(sample, offset));
  }
}

}  // namespace candela
