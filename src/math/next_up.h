// The next double above a finite value, without a library call: std::nextafter(t, +inf) is an
// out-of-line libm function, and the accelerators call it at every accepted hit (the nearest-hit
// test limit is nextafter(best t), so that an equal t with a lower index is still seen).
#pragma once

#include <bit>
#include <cstdint>
#include <limits>

namespace candela {

// std::nextafter(t, +inf) for every t but NaN: one step on the bit pattern, +1 for t >= 0 and
// -1 for t < 0 (-0 counts as +0, whose successor is the smallest denormal); +inf stays +inf.
inline double next_up(double t) {
  if (!(t < std::numeric_limits<double>::infinity())) return t;         // +inf (and NaN) unchanged
  auto bits = std::bit_cast<uint64_t>(t + 0.0);                         // -0 becomes +0
  bits += 1 | static_cast<uint64_t>(static_cast<int64_t>(bits) >> 63);  // +1, or -1 when negative
  return std::bit_cast<double>(bits);
}

// The same step for a float (bvh-fast's box limit after a hit, one float step above its t).
inline float next_up(float t) {
  if (!(t < std::numeric_limits<float>::infinity())) return t;
  auto bits = std::bit_cast<uint32_t>(t + 0.0f);
  bits += 1 | static_cast<uint32_t>(static_cast<int32_t>(bits) >> 31);
  return std::bit_cast<float>(bits);
}

}  // namespace candela
