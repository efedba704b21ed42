// The sRGB transfer curves (IEC 61966-2-1), for every module that turns linear values into
// display values or back: tone mapping (camera/), image reading (io/), color maps and
// texture tests.
#pragma once

#include <cmath>

namespace candela {

// Linear value in [0, 1] → encoded value (the inverse EOTF): a linear segment below 0.0031308,
// power 1/2.4 above.
inline double srgb_encode(double linear) {
  if (linear <= 0.0031308) return 12.92 * linear;
  return 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
}

// The sRGB electro-optical transfer function: encoded value in [0, 1] → linear. A linear
// segment below the 0.04045 threshold, power 2.4 above.
inline double srgb_decode(double encoded) {
  return encoded <= 0.04045 ? encoded / 12.92 : std::pow((encoded + 0.055) / 1.055, 2.4);
}

}  // namespace candela
