// ∫ f(ω) dω over the unit sphere by the midpoint rule in (cos θ, φ) about +z: bands × sectors
// cells of equal solid angle 4π / (bands · sectors), each taken at its centre. Exact for a
// constant; converges as 1/bands² + 1/sectors² for a smooth f. What the environment light's mean
// radiance and the tests' flux and sampling checks integrate with.
#pragma once

#include <cmath>

#include "math/constants.h"
#include "math/vector.h"

namespace candela {

template <typename F>
auto integrate_over_sphere(const F& f, int bands, int sectors) {
  decltype(f(Vec3{})) sum{};
  for (int band = 0; band < bands; ++band) {
    const double z = 1 - 2 * (band + 0.5) / bands;
    const double ring = std::sqrt(1 - z * z);
    for (int sector = 0; sector < sectors; ++sector) {
      const double phi = 2 * kPi * (sector + 0.5) / sectors;
      sum += f(Vec3{ring * std::cos(phi), ring * std::sin(phi), z});
    }
  }
  return sum * (4 * kPi / (double(bands) * sectors));
}

}  // namespace candela
