// The contrast test of adaptive anti-aliasing (000 §5.8.2, after Mitchell 1987, "Generating
// antialiased images at low sampling densities", SIGGRAPH '87): C = (Imax − Imin)/(Imax + Imin)
// of each channel over four samples, against that channel's threshold (aa.threshold). The ray
// tracers' adaptive sampler tests a square's four corners (camera/antialiasing.cpp), the
// accumulation buffer a pixel's four first samples (camera/accumulation_buffer.cpp).
#pragma once

#include <algorithm>

#include "math/vector.h"

namespace candela {

// C of one channel over four values; 0 where all four are 0 (or their extremes cancel).
inline double channel_contrast(double a, double b, double c, double d) {
  const double high = std::max({a, b, c, d});
  const double low = std::min({a, b, c, d});
  const double sum = high + low;
  return sum > 0 ? (high - low) / sum : 0.0;
}

// Whether C of any channel exceeds that channel's threshold.
inline bool contrast_exceeds(const Color& threshold, const Color& c00, const Color& c10, const Color& c01,
                             const Color& c11) {
  for (int channel = 0; channel < 3; ++channel)
    if (channel_contrast(c00[channel], c10[channel], c01[channel], c11[channel]) > threshold[channel])
      return true;
  return false;
}

}  // namespace candela
