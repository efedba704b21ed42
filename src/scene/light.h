// Emitters (SPEC §7): one interface for the scene file's lights (point, spot,
// directional, area) and for emissive surfaces (surface_light.h), which the local model, the
// rasterizer, radiosity's first shot and meshless η all read the same way. Ambient light is not
// an emitter: it is the local model's constant term, a scene-wide color.
#pragma once

#include <bit>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "math/vector.h"
#include "util/hash.h"

namespace candela {

// Light arriving at a point from one source, before shadowing. Every light sets all of it.
struct LightSample {
  Vec3 direction;       // L: unit, from the point toward the light
  double distance = 0;  // to the light; infinity for a directional light
  Color intensity;      // Ip · f_at (· spot factor)
  // The solid-angle density of `direction` when the light is one a ray can hit (an emissive
  // surface, the environment), so that a BSDF-sampled ray that finds it can weigh itself against
  // the light's sampling (MIS): 1/(cells · pdf) is in `intensity` already. 0 for the point-like
  // lights and the area light, which no ray can hit.
  double pdf = 0;
  // The emitter's surface normal at the sampled point (emissive surfaces, whose shadow rays stop
  // short of the surface on the side they arrive from); zero for the others.
  Vec3 normal{};
};

// Where in each cell (stratum) of a light's fixed sample set a shading point takes its sample: the
// centre (`jittered` false), or a point of the cell drawn from a hash of the shading point, the
// light, the cell and the seed — different from pixel to pixel, so that penumbrae are noise
// rather than stepped bands, yet a pure function of the point, so images do not depend on the
// thread count or on the order in which points are shaded.
struct StratumJitter {
  bool jittered = false;
  uint64_t seed = 0;
  Vec2 at(const Vec3& point, std::size_t light, int cell) const {
    if (!jittered) return {0.5, 0.5};
    uint64_t key = mix64(seed ^ 0x6a09e667f3bcc909ULL);
    for (const double coordinate : {point.x, point.y, point.z})
      key = mix64(key ^ std::bit_cast<uint64_t>(coordinate));
    key = mix64(key ^ (static_cast<uint64_t>(light) << 32 | static_cast<uint32_t>(cell)));
    return {static_cast<double>(key >> 40) * 0x1p-24, static_cast<double>(key & 0xffffffULL) * 0x1p-24};
  }
};

// Cell `index` of samples × samples equal cells of [0, 1)², row by row, at `within` of the cell:
// the point a stratified light's sample is taken at (area lights, surfaces, the environment).
inline Vec2 stratum_point(int index, int samples, const Vec2& within) {
  return {(index % samples + within.x) / samples, (index / samples + within.y) / samples};
}

class Light {
 public:
  virtual ~Light() = default;
  // False when the point receives nothing (outside a spot cone). A light made of many points
  // (an area light, an emissive surface) answers here as one point at its centre carrying all of
  // it; methods that trace shadows use the samples below instead.
  virtual bool illuminate(const Vec3& point, LightSample& sample) const = 0;
  virtual std::string_view type_name() const = 0;

  // The power the light sends (pbrt's Light::Phi), in the images' units times area: an emitter of
  // exitance E and area A sends E·A. For the lights that fall off slower than 1/d² or not at all
  // (a point light without inverse-square attenuation, a directional light, the environment) it is
  // the power that reaches a sphere of radius scene_radius around the scene (the light at its
  // centre): the measure the path tracer chooses its lights by.
  virtual Color power(double scene_radius) const = 0;
  // What a ray that reaches the light travelling along `direction` (a unit vector from the scene
  // toward the light) brings back, in the images' units: an emissive surface's emission (alike on
  // both sides), the environment's radiance seen along the direction; black for the lights no ray
  // can hit (point-like lights, the area light).
  virtual Color emitted_radiance(const Vec3& direction) const {
    (void)direction;
    return {};
  }

  // The light as sample_count() point samples whose intensities add up to what it sends: one for
  // the point-like lights; for an area light or an emissive surface one per cell of a fixed
  // stratification, sample `index` taken at `within` ∈ [0, 1)² of its cell ({0.5, 0.5}: the
  // centre; StratumJitter says where).
  virtual int sample_count() const { return 1; }
  // Whether illuminate_sample reads `within` (the lights made of many points or directions: area,
  // surface, environment, luminaire with a size, the sun's disc); the others are never handed
  // StratumJitter's hash (see illuminate_cell). A light that overrides illuminate_sample and
  // reads `within` must say so, or its samples stay at the cells' centres.
  virtual bool stratified() const { return false; }
  virtual bool illuminate_sample(const Vec3& point, int index, const Vec2& within,
                                 LightSample& sample) const {
    (void)within;
    return index == 0 && illuminate(point, sample);
  }
  // One random point of the light (u uniform in [0, 1)²) carrying the whole light, so that its
  // expectation over u is what the sample_count() samples give together: the path tracer's
  // next-event estimate (SPEC §12). Point-like lights answer with their one sample.
  virtual bool illuminate_random(const Vec3& point, const Vec2& u, LightSample& sample) const {
    (void)u;
    return illuminate(point, sample);
  }
};

// Sample `index` of emitter `light_index` for `point`, at the place in its cell `jitter` gives —
// hashed only for a stratified light: for a point light the hash cost as much as the rest of its
// sample (the Whitted two-mirror scene spent some 5 % of its time there).
inline bool illuminate_cell(const Light& light, const Vec3& point, std::size_t light_index, int index,
                            const StratumJitter& jitter, LightSample& sample) {
  const Vec2 within = light.stratified() ? jitter.at(point, light_index, index) : Vec2{0.5, 0.5};
  return light.illuminate_sample(point, index, within, sample);
}

}  // namespace candela
