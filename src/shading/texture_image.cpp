#include "shading/texture_image.h"

#include <algorithm>
#include <cmath>

namespace candela {

namespace {

// One axis of a bilinear lookup: the two texel indices to blend and the weight of the second.
struct AxisSamples {
  int first, second;
  double weight_of_second;
};

// A texel index outside [0, size) brought back inside by the wrap mode.
int wrap_index(int index, int size, WrapMode wrap) {
  switch (wrap) {
    case WrapMode::repeat: {
      const int m = index % size;
      return m < 0 ? m + size : m;
    }
    case WrapMode::clamp:
      return std::clamp(index, 0, size - 1);
    case WrapMode::mirror: {
      // Period 2·size: indices size..2·size−1 run back from size−1 to 0.
      const int period = 2 * size;
      int m = index % period;
      if (m < 0) m += period;
      return m < size ? m : period - 1 - m;
    }
  }
  return 0;
}

AxisSamples axis_samples(double coordinate, int size, WrapMode wrap) {
  if (!std::isfinite(coordinate)) coordinate = 0;
  // Reduce to one period first, so that huge coordinates cannot overflow the int conversion.
  // The reductions are exact for coordinates already inside [0, 1).
  switch (wrap) {
    case WrapMode::repeat:
      coordinate -= std::floor(coordinate);
      break;  // [0, 1]
    case WrapMode::mirror:
      coordinate -= 2 * std::floor(coordinate / 2);
      break;  // [0, 2]
    case WrapMode::clamp:
      coordinate = std::clamp(coordinate, 0.0, 1.0);
      break;  // [0, 1]
  }
  // Texel i has its centre at (i + 0.5)/size.
  const double position = coordinate * size - 0.5;
  const double below = std::floor(position);
  const int index = static_cast<int>(below);
  return {wrap_index(index, size, wrap), wrap_index(index + 1, size, wrap), position - below};
}

}  // namespace

Color TextureImage::bilinear(const Vec2& uv, WrapMode wrap_u, WrapMode wrap_v) const {
  const AxisSamples sx = axis_samples(uv.x, width(), wrap_u);
  const AxisSamples sy = axis_samples(uv.y, height(), wrap_v);
  const Color c00 = texel(sx.first, sy.first), c10 = texel(sx.second, sy.first);
  const Color c01 = texel(sx.first, sy.second), c11 = texel(sx.second, sy.second);
  // a + t·(b − a) rather than (1 − t)·a + t·b: equal texels give exactly that texel (a constant
  // image stays constant), and t = 0 gives exactly a.
  const auto lerp = [](const Color& a, const Color& b, double t) { return a + (b - a) * t; };
  return lerp(lerp(c00, c10, sx.weight_of_second), lerp(c01, c11, sx.weight_of_second), sy.weight_of_second);
}

}  // namespace candela
