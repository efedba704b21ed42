// Input directions and normals to unit vectors, safely: the one way a direction read
// from a file (a probe normal, a light's direction, a rotation axis, a plane's normal) is
// normalised.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "math/vector.h"

namespace candela {

// The direction of v as a unit vector, or nullopt when v is zero or not finite. Where the squared
// length would overflow ((1e200, 1e200, 0): length(v) is infinite, v / length(v) zero) or
// underflow ((1e-200, 0, 0): length(v) is 0, a non-zero vector called zero), v is first divided
// by its largest component, so every finite non-zero vector has a direction. Elsewhere the result
// is exactly normalize(v).
inline std::optional<Vec3> direction_of(const Vec3& v) {
  if (!is_finite(v)) return std::nullopt;
  const double squared = length_squared(v);
  if (squared >= std::numeric_limits<double>::min() && squared <= std::numeric_limits<double>::max())
    return v / std::sqrt(squared);
  const double largest = std::max({std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)});
  if (largest == 0) return std::nullopt;
  const Vec3 scaled = v / largest;
  return scaled / length(scaled);
}

}  // namespace candela
