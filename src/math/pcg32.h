// PCG32 (O'Neill 2014, pcg-random.org): XSH RR output, 64-bit LCG state.
#pragma once

#include <cstdint>

namespace candela {

class Pcg32 {
 public:
  Pcg32() { seed(0x853c49e6748fea9bULL, 0xda3e39cb94b95bdbULL); }
  Pcg32(uint64_t state_seed, uint64_t sequence) { seed(state_seed, sequence); }

  void seed(uint64_t state_seed, uint64_t sequence) {
    state_ = 0;
    increment_ = (sequence << 1u) | 1u;
    next_uint();
    state_ += state_seed;
    next_uint();
  }

  uint32_t next_uint() {
    const uint64_t old = state_;
    state_ = old * 6364136223846793005ULL + increment_;
    const auto xorshifted = static_cast<uint32_t>(((old >> 18u) ^ old) >> 27u);
    const auto rotation = static_cast<uint32_t>(old >> 59u);
    return (xorshifted >> rotation) | (xorshifted << ((32u - rotation) & 31u));
  }

  // Uniform in [0, 1): 32 random bits scaled, never rounds up to 1.
  double next_double() { return next_uint() * 0x1p-32; }

 private:
  uint64_t state_ = 0;
  uint64_t increment_ = 0;
};

// The per-pixel stream: the image is identical whatever the thread count (SPEC §6).
inline Pcg32 pixel_rng(uint64_t seed, uint32_t x, uint32_t y) {
  return Pcg32(seed, (static_cast<uint64_t>(y) << 32) | x);
}

}  // namespace candela
