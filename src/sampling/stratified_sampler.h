// The stratified sampler (pbrt-v4's StratifiedSampler, for progressive passes): with N samples
// per pixel, each 1D dimension is cut into N strata and each 2D one into a grid of at least N
// cells (⌈√N⌉ columns); pass k of a pixel takes, in every dimension, the stratum that a
// permutation seeded by the pixel and the dimension gives k, and a random point in it. The
// passes of a pixel thus cover each dimension evenly; different dimensions and pixels are
// shuffled independently. Needs N (path.spp); the point within each stratum is PCG32's.
#pragma once

#include "math/pcg32.h"
#include "sampling/sampler.h"

namespace candela {

// A permutation of [0, n) as a function of a seed: the element at position `index` (Kensler 2013's
// hashed permutation: a bijection of the next power of two, walked until it lands below n).
uint32_t permutation_element(uint32_t index, uint32_t n, uint32_t seed);

class StratifiedSampler final : public Sampler {
 public:
  StratifiedSampler(uint64_t seed, uint64_t samples);

  std::string_view name() const override { return "stratified"; }
  void start_pixel_sample(uint32_t x, uint32_t y, uint64_t index) override;
  double get_1d() override;
  Vec2 get_2d() override;
  std::unique_ptr<Sampler> clone() const override { return std::make_unique<StratifiedSampler>(*this); }

 private:
  uint32_t dimension_seed();  // the next dimension's permutation seed
  uint64_t seed_;
  uint32_t samples_, columns_, rows_;
  uint32_t index_ = 0;
  uint64_t pixel_key_ = 0;
  uint32_t dimension_ = 0;
  Pcg32 jitter_;
};

}  // namespace candela
