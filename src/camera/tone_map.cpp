#include "camera/tone_map.h"

#include <algorithm>
#include <cmath>

namespace candela {

std::vector<Color> expose(const Film& film, double exposure) {
  const double factor = std::exp2(exposure);
  std::vector<Color> pixels = film.pixels();
  for (Color& c : pixels) c *= factor;
  return pixels;
}

std::vector<uint8_t> to_display(const Film& film, const DisplaySettings& settings) {
  std::vector<Color> pixels = expose(film, settings.exposure);
  if (settings.out_of_range == OutOfRange::scale) {
    double largest = 0;
    for (const Color& c : pixels) largest = std::max(largest, c.max_component());
    if (largest > 1)
      for (Color& c : pixels) c = c / largest;
  } else if (settings.out_of_range == OutOfRange::normalize) {
    for (Color& c : pixels) {
      const double largest = c.max_component();
      if (largest > 1) c = c / largest;
    }
  }
  std::vector<uint8_t> bytes;
  bytes.reserve(pixels.size() * 3);
  for (const Color& c : pixels) {
    for (int channel = 0; channel < 3; ++channel) {
      double value = std::clamp(c[channel], 0.0, 1.0);  // NaN-safe below
      if (!(value >= 0)) value = 0;
      if (settings.srgb) value = srgb_encode(value);
      bytes.push_back(static_cast<uint8_t>(std::lround(value * 255.0)));
    }
  }
  return bytes;
}

}  // namespace candela
