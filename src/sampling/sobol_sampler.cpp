#include "sampling/sobol_sampler.h"

#include "util/hash.h"

namespace candela {

uint32_t reverse_bits(uint32_t x) {
  x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
  x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
  x = ((x >> 4) & 0x0f0f0f0fu) | ((x & 0x0f0f0f0fu) << 4);
  x = ((x >> 8) & 0x00ff00ffu) | ((x & 0x00ff00ffu) << 8);
  return (x >> 16) | (x << 16);
}

uint32_t sobol_dimension_0(uint32_t index) {
  return reverse_bits(index);
}

namespace {

// Direction numbers of x + 1: v₁ = 1/2, v_k = v_{k−1} ⊕ (v_{k−1} / 2); the point of index i is
// the xor of v_k over the bits k of i, looked up a byte of the index at a time (a shuffled index
// has all 32 bits: a loop over them cost the path tracer a third of its time).
struct SobolDimension1Table {
  uint32_t byte[4][256] = {};
  constexpr SobolDimension1Table() {
    uint32_t direction[32] = {};
    direction[0] = 0x80000000u;
    for (int k = 1; k < 32; ++k) direction[k] = direction[k - 1] ^ (direction[k - 1] >> 1);
    for (int b = 0; b < 4; ++b)
      for (uint32_t value = 0; value < 256; ++value)
        for (int bit = 0; bit < 8; ++bit)
          if (value & (1u << bit)) byte[b][value] ^= direction[8 * b + bit];
  }
};
constexpr SobolDimension1Table kDimension1;

// A 32-bit hash (Wellons' lowbias32): every input bit reaches every output bit.
uint32_t hash32(uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  return x ^ (x >> 16);
}

}  // namespace

uint32_t sobol_dimension_1(uint32_t index) {
  return kDimension1.byte[0][index & 0xffu] ^ kDimension1.byte[1][(index >> 8) & 0xffu] ^
         kDimension1.byte[2][(index >> 16) & 0xffu] ^ kDimension1.byte[3][index >> 24];
}

uint32_t nested_uniform_scramble(uint32_t x, uint32_t seed) {
  // Burley 2020, §3: on the reversed bits, adding the seed and xoring in products with even
  // constants changes each bit by the bits below it only — in the fraction's order, each digit is
  // permuted by a function of the digits before it, which is Owen's scrambling.
  x = reverse_bits(x);
  x += seed;
  x ^= x * 0x6c50b47cu;
  x ^= x * 0xb82f1e52u;
  x ^= x * 0xc7afe638u;
  x ^= x * 0x8d22f6e6u;
  return reverse_bits(x);
}

void SobolSampler::start_pixel_sample(uint32_t x, uint32_t y, uint64_t index) {
  pixel_key_ = pixel_sample_key(seed_, x, y);
  index_ = static_cast<uint32_t>(index);  // 2^32 passes of one pixel would repeat
  dimension_ = 0;
}

uint32_t SobolSampler::dimension_seed() {
  return hash32(static_cast<uint32_t>(pixel_key_) ^
                hash32(static_cast<uint32_t>(pixel_key_ >> 32) + ++dimension_));
}

double SobolSampler::get_1d() {
  const uint32_t seed = dimension_seed();
  // The index shuffled by the same kind of scrambling keeps aligned blocks of 2^m indices
  // together, so the first 2^m passes are still one net.
  const uint32_t index = nested_uniform_scramble(index_, seed);
  return nested_uniform_scramble(sobol_dimension_0(index), hash32(seed ^ 0x68e31da4u)) * 0x1p-32;
}

Vec2 SobolSampler::get_2d() {
  const uint32_t seed = dimension_seed();
  const uint32_t index = nested_uniform_scramble(index_, seed);
  return {nested_uniform_scramble(sobol_dimension_0(index), hash32(seed ^ 0x68e31da4u)) * 0x1p-32,
          nested_uniform_scramble(sobol_dimension_1(index), hash32(seed ^ 0xb5297a4du)) * 0x1p-32};
}

}  // namespace candela
