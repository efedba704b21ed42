// The Sobol' sampler (Burley 2020, "Practical Hash-based Owen Scrambling"): every 1D or 2D value
// of a sample is a point of the first two Sobol' dimensions — a (0, 2)-sequence in base 2, so the
// first 2^m passes of a pixel put one point in every elementary interval of area 2^-m — whose
// index is shuffled and whose coordinates are Owen-scrambled by a hash seeded by the pixel and
// the dimension. The scrambling keeps the stratification and makes pixels and dimensions
// independent of one another ("padding"); on smooth integrands the error falls about as N^-1
// instead of N^-1/2. Needs no sample count; best with powers of two.
#pragma once

#include <cstdint>

#include "sampling/sampler.h"

namespace candela {

// Bits reversed (bit 0 becomes bit 31).
uint32_t reverse_bits(uint32_t x);
// The first two dimensions of the Sobol' sequence, as 32-bit fractions: the van der Corput
// sequence and the one of the polynomial x + 1.
uint32_t sobol_dimension_0(uint32_t index);
uint32_t sobol_dimension_1(uint32_t index);
// Owen's nested uniform scrambling of a 32-bit fraction, by a hash in which each bit depends only
// on the bits above it (Laine and Karras 2011's permutation applied to the reversed bits).
uint32_t nested_uniform_scramble(uint32_t x, uint32_t seed);

class SobolSampler final : public Sampler {
 public:
  explicit SobolSampler(uint64_t seed) : seed_(seed) {}

  std::string_view name() const override { return "sobol"; }
  void start_pixel_sample(uint32_t x, uint32_t y, uint64_t index) override;
  double get_1d() override;
  Vec2 get_2d() override;
  std::unique_ptr<Sampler> clone() const override { return std::make_unique<SobolSampler>(*this); }

 private:
  uint32_t dimension_seed();  // the next dimension's scrambling seed
  uint32_t shuffled_index(uint32_t seed) const;
  uint64_t seed_;
  uint32_t pixel_seed_ = 0;      // the pixel's key, folded to 32 bits
  uint32_t reversed_index_ = 0;  // the pass's index, bits reversed
  uint32_t dimension_ = 0;
};

}  // namespace candela
