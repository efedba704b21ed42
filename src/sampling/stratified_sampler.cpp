#include "sampling/stratified_sampler.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "util/hash.h"

namespace candela {

namespace {

// The largest double below 1: (stratum + u) / n can round up to 1 when n is large.
constexpr double kBelowOne = 1.0 - std::numeric_limits<double>::epsilon() / 2;

// A bijection of [0, mask + 1) (mask = 2^w − 1) chosen by `seed`: each step is invertible modulo
// 2^w — xor with a constant, multiplication by an odd number, xor with the value shifted right —
// multiplications carry the low bits up, shifts carry the high bits down.
uint32_t permute_bits(uint32_t x, uint32_t mask, uint32_t seed) {
  constexpr uint32_t kOdd[3] = {0x9e3779b1u, 0x85ebca77u, 0xc2b2ae3du};
  for (int round = 0; round < 3; ++round) {
    x = (x ^ (seed >> (8 * round))) & mask;
    x = (x * kOdd[round]) & mask;
    x ^= x >> 1;
    x ^= x >> 3;
    x = (x * (seed | 1u)) & mask;
    x ^= x >> 7;
  }
  return x;
}

}  // namespace

uint32_t permutation_element(uint32_t index, uint32_t n, uint32_t seed) {
  if (n <= 1) return 0;
  uint32_t mask = n - 1;
  mask |= mask >> 1;
  mask |= mask >> 2;
  mask |= mask >> 4;
  mask |= mask >> 8;
  mask |= mask >> 16;
  // Cycle walking: the bijection's cycle through `index` (< n) comes back below n, so this ends;
  // at most 2 steps are expected, as more than half of [0, mask] lies below n.
  uint32_t x = index;
  do {
    x = permute_bits(x, mask, seed);
  } while (x >= n);
  return x;
}

StratifiedSampler::StratifiedSampler(uint64_t seed, uint64_t samples)
    : seed_(seed), samples_(static_cast<uint32_t>(std::clamp<uint64_t>(samples, 1, uint64_t{1} << 30))) {
  columns_ = static_cast<uint32_t>(std::ceil(std::sqrt(static_cast<double>(samples_))));
  rows_ = (samples_ + columns_ - 1) / columns_;
}

void StratifiedSampler::start_pixel_sample(uint32_t x, uint32_t y, uint64_t index) {
  pixel_key_ = pixel_sample_key(seed_, x, y);
  index_ = static_cast<uint32_t>(index % samples_);
  dimension_ = 0;
  jitter_ = Pcg32(pixel_key_, index);
}

uint32_t StratifiedSampler::dimension_seed() {
  return static_cast<uint32_t>(mix64(pixel_key_ ^ (++dimension_ * 0x9e3779b97f4a7c15ULL)));
}

double StratifiedSampler::get_1d() {
  const uint32_t stratum = permutation_element(index_, samples_, dimension_seed());
  return std::min((stratum + jitter_.next_double()) / samples_, kBelowOne);
}

Vec2 StratifiedSampler::get_2d() {
  const uint32_t cell = permutation_element(index_, columns_ * rows_, dimension_seed());
  const double u = jitter_.next_double(), v = jitter_.next_double();
  return {std::min((cell % columns_ + u) / columns_, kBelowOne),
          std::min((cell / columns_ + v) / rows_, kBelowOne)};
}

}  // namespace candela
