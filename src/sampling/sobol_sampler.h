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

// Bits reversed (bit 0 becomes bit 31): the bits of each byte, then the bytes (one bswap).
inline uint32_t reverse_bits(uint32_t x) {
  x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
  x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
  x = ((x >> 4) & 0x0f0f0f0fu) | ((x & 0x0f0f0f0fu) << 4);
  return __builtin_bswap32(x);
}
// The first two dimensions of the Sobol' sequence, as 32-bit fractions: the van der Corput
// sequence and the one of the polynomial x + 1.
uint32_t sobol_dimension_0(uint32_t index);
uint32_t sobol_dimension_1(uint32_t index);
// Owen's nested uniform scrambling of a 32-bit fraction, by a hash in which each bit depends only
// on the bits above it (Laine and Karras 2011's permutation applied to the reversed bits).
uint32_t nested_uniform_scramble(uint32_t x, uint32_t seed);

namespace sobol_detail {

// Direction numbers of x + 1: v₁ = 1/2, v_k = v_{k−1} ⊕ (v_{k−1} / 2); the point of index i is
// the xor of v_k over the bits k of i, looked up a byte of the index at a time (a shuffled index
// has all 32 bits: a loop over them cost the path tracer a third of its time). `reversed` holds
// the same points with their bits reversed, which the scrambling starts from.
struct Dimension1Table {
  uint32_t byte[4][256] = {};
  constexpr Dimension1Table(bool reversed) {
    uint32_t direction[32] = {};
    direction[0] = 0x80000000u;
    for (int k = 1; k < 32; ++k) direction[k] = direction[k - 1] ^ (direction[k - 1] >> 1);
    if (reversed)
      for (uint32_t& d : direction) {
        uint32_t r = 0;
        for (int bit = 0; bit < 32; ++bit)
          if (d & (1u << bit)) r |= 1u << (31 - bit);
        d = r;
      }
    for (int b = 0; b < 4; ++b)
      for (uint32_t value = 0; value < 256; ++value)
        for (int bit = 0; bit < 8; ++bit)
          if (value & (1u << bit)) byte[b][value] ^= direction[8 * b + bit];
  }
  uint32_t operator()(uint32_t index) const {
    return byte[0][index & 0xffu] ^ byte[1][(index >> 8) & 0xffu] ^ byte[2][(index >> 16) & 0xffu] ^
           byte[3][index >> 24];
  }
};
inline constexpr Dimension1Table kDimension1(false);
inline constexpr Dimension1Table kDimension1Reversed(true);

// Burley 2020, §3 (Laine and Karras 2011's permutation): on reversed bits, adding the seed and
// xoring in products with even constants changes each bit by the bits below it only — in the
// fraction's order, each digit is permuted by a function of the digits before it, which is Owen's
// scrambling.
inline uint32_t laine_karras_permutation(uint32_t x, uint32_t seed) {
  x += seed;
  x ^= x * 0x6c50b47cu;
  x ^= x * 0xb82f1e52u;
  x ^= x * 0xc7afe638u;
  x ^= x * 0x8d22f6e6u;
  return x;
}

// A 32-bit hash (Wellons' lowbias32): every input bit reaches every output bit.
inline uint32_t hash32(uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  return x ^ (x >> 16);
}

inline uint32_t hash_combine(uint32_t seed, uint32_t value) {
  return seed ^ (value + (seed << 6) + (seed >> 2));
}

}  // namespace sobol_detail

// The values are defined here, not in the .cpp, so that the path tracer's loop (a template on
// the sampler's type) inlines them: through the virtual call a 2D value went back by memory.
class SobolSampler final : public Sampler {
 public:
  explicit SobolSampler(uint64_t seed) : seed_(seed) {}

  std::string_view name() const override { return "sobol"; }
  void start_pixel_sample(uint32_t x, uint32_t y, uint64_t index) override;
  double get_1d() override {
    using namespace sobol_detail;
    const uint32_t seed = dimension_seed();
    const uint32_t index = shuffled_index(seed);
    return reverse_bits(laine_karras_permutation(index, hash_combine(seed, 0x68e31da4u))) * 0x1p-32;
  }
  Vec2 get_2d() override {
    using namespace sobol_detail;
    const uint32_t seed = dimension_seed();
    const uint32_t index = shuffled_index(seed);
    return {
        reverse_bits(laine_karras_permutation(index, hash_combine(seed, 0x68e31da4u))) * 0x1p-32,
        reverse_bits(laine_karras_permutation(kDimension1Reversed(index), hash_combine(seed, 0xb5297a4du))) *
            0x1p-32};
  }
  std::unique_ptr<Sampler> clone() const override { return std::make_unique<SobolSampler>(*this); }

 private:
  // One full hash per dimension (pixel and dimension are its input); the coordinates' seeds are
  // derived from it by Boost's hash_combine, as Burley 2020's reference code does: the
  // Laine-Karras permutation mixes them further, and the three seeds of a 2D value differ in many
  // bits. Three hashes of a 2D value down to one: the sampler had 11 % of the path tracer's time.
  uint32_t dimension_seed() { return sobol_detail::hash32(pixel_seed_ + 0x9e3779b9u * ++dimension_); }
  // What get_1d and get_2d compute is nested_uniform_scramble(sobol_dimension_d(index), seed_d)
  // of the index shuffled by nested_uniform_scramble(index, seed) — which keeps aligned blocks
  // of 2^m indices together, so the first 2^m passes are still one net. The bit reversals that
  // cancel are left out: dimension 0 is the reversal itself, and dimension 1 has a reversed table.
  uint32_t shuffled_index(uint32_t seed) const {
    return reverse_bits(sobol_detail::laine_karras_permutation(reversed_index_, seed));
  }
  uint64_t seed_;
  uint32_t pixel_seed_ = 0;      // the pixel's key, folded to 32 bits
  uint32_t reversed_index_ = 0;  // the pass's index, bits reversed
  uint32_t dimension_ = 0;
};

}  // namespace candela
