// Mirror and refraction directions (000 §5.3).
#pragma once

#include <cmath>

#include "math/vector.h"

namespace candela {

// 000 eq. 5-5: R = 2N(N·V) − V; V points away from the surface (toward the viewer).
inline Vec3 reflect(const Vec3& V, const Vec3& N) {
  return 2 * dot(N, V) * N - V;
}

// 000 eq. 5-7: T = (η1/η2)[N(N·V) − V] − N sqrt(1 − (η1/η2)²[1 − (N·V)²]), with N on the
// side of V and eta = η1/η2. Returns false on total internal reflection (|S'| > 1).
inline bool refract(const Vec3& V, const Vec3& N, double eta, Vec3& T) {
  const double cos_incident = dot(N, V);
  const double sin2_transmitted = eta * eta * (1 - cos_incident * cos_incident);
  if (sin2_transmitted > 1) return false;
  T = eta * (N * cos_incident - V) - N * std::sqrt(1 - sin2_transmitted);
  return true;
}

}  // namespace candela
