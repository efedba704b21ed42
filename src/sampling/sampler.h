// Sample streams of the path tracer (pbrt-v4's base/sampler.h is the model), found by
// name in a registry: `independent` (PCG32 numbers, the path tracer's stream before samplers),
// `stratified` (each dimension jittered in strata that the passes of a pixel take in a shuffled
// order) and `sobol` (Sobol' points, Owen-scrambled by hashing, Burley 2020).
//
// A sample is one pass of one pixel: start_pixel_sample(x, y, index) begins it, and every value
// after that is a pure function of the seed, the pixel, the index and how many values the sample
// has drawn — never of the thread, the tile, the rank or a resume from a checkpoint. Values are
// drawn in the order the path asks for them: the point in the pixel, then per bounce the light
// choice (1D), the point on the light (2D), the BSDF lobe (1D), the BSDF direction (2D) and
// Russian roulette (1D); a value not needed is not drawn (no light to sample, one emitter
// to choose from, a BSDF of one lobe).
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>

#include "math/vector.h"
#include "util/hash.h"

namespace candela {

class Sampler {
 public:
  virtual ~Sampler() = default;
  virtual std::string_view name() const = 0;
  // Begins sample `index` (the pass, counted from 0) of pixel (x, y).
  virtual void start_pixel_sample(uint32_t x, uint32_t y, uint64_t index) = 0;
  // The next value of the sample, uniform in [0, 1).
  virtual double get_1d() = 0;
  // The next pair, uniform in [0, 1)²; the first pair of a sample is the point in the pixel.
  virtual Vec2 get_2d() = 0;
  // A sampler of the same kind and parameters, for another thread.
  virtual std::unique_ptr<Sampler> clone() const = 0;
};

// The key of pixel (x, y) under `seed` that the stratified and Sobol' samplers derive their
// per-dimension seeds from.
inline uint64_t pixel_sample_key(uint64_t seed, uint32_t x, uint32_t y) {
  return mix64(seed ^ mix64((static_cast<uint64_t>(y) << 32) | x));
}

struct SamplerParameters {
  uint64_t seed = 0;     // render.seed
  uint64_t samples = 0;  // the samples per pixel (path.spp); 0: not known (rendering for a time)
};

struct SamplerEntry {
  const char* name;
  const char* description;
  bool needs_sample_count;  // refused when SamplerParameters::samples is 0
  std::unique_ptr<Sampler> (*create)(const SamplerParameters& parameters);
};

std::span<const SamplerEntry> sampler_entries();
const SamplerEntry* find_sampler(std::string_view name);  // nullptr when unknown
std::string sampler_names();                              // "independent, stratified, sobol"
// Throws std::invalid_argument for an unknown name, or a sampler that needs the sample count
// given none.
std::unique_ptr<Sampler> create_sampler(std::string_view name, const SamplerParameters& parameters);

}  // namespace candela
