// Real spherical harmonics up to band 2 (nine functions), per colour channel: how hierarchical
// radiosity's clusters (SPEC §10.1; Sillion 1995) hold a directional distribution — the intensity
// a cluster of surfaces sends each way, and the light it receives from each way — in a fixed
// size, whatever the number of surfaces inside.
//
// A clamped cosine lobe max(0, n·ω) has the coefficients Â_l Y_lm(n) with Â_0 = π, Â_1 = 2π/3,
// Â_2 = π/4 (Ramamoorthi and Hanrahan 2001, "An efficient representation for irradiance
// environment maps", eq. 8): the irradiance E(n) = ∫ L(ω) max(0, n·ω) dω of a radiance
// distribution with coefficients L_lm is Σ Â_l L_lm Y_lm(n), exact for the band-limited part of L
// (its error for arbitrary lighting is a few percent, the bands above 2 of the lobe being small).
#pragma once

#include <array>

#include "math/constants.h"
#include "math/vector.h"

namespace candela {

using ShBasis = std::array<double, 9>;
using ShColor = std::array<Color, 9>;  // one coefficient per basis function, RGB

// Y_00 … Y_22 at the unit direction d (orthonormal over the sphere).
inline ShBasis sh_basis(const Vec3& d) {
  return {0.282094791773878,
          0.488602511902920 * d.y,
          0.488602511902920 * d.z,
          0.488602511902920 * d.x,
          1.092548430592079 * d.x * d.y,
          1.092548430592079 * d.y * d.z,
          0.315391565252520 * (3 * d.z * d.z - 1),
          1.092548430592079 * d.x * d.z,
          0.546274215296040 * (d.x * d.x - d.y * d.y)};
}

// Â_l of the clamped cosine for each of the nine functions (band 0, 1, 1, 1, 2 × 5).
inline constexpr std::array<double, 9> kClampedCosineBands = {
    kPi, 2 * kPi / 3, 2 * kPi / 3, 2 * kPi / 3, kPi / 4, kPi / 4, kPi / 4, kPi / 4, kPi / 4};

// coefficients += weight · max(0, n·ω) as a function of ω.
inline void add_clamped_cosine(ShColor& coefficients, const Vec3& n, const Color& weight) {
  const ShBasis y = sh_basis(n);
  for (std::size_t k = 0; k < 9; ++k) coefficients[k] += weight * (kClampedCosineBands[k] * y[k]);
}

// coefficients += weight · δ(ω − d): light arriving from direction d.
inline void add_delta(ShColor& coefficients, const Vec3& d, const Color& weight) {
  const ShBasis y = sh_basis(d);
  for (std::size_t k = 0; k < 9; ++k) coefficients[k] += weight * y[k];
}

// The function at direction d, clamped at 0 per channel (the truncated series rings below zero).
inline Color sh_evaluate(const ShColor& coefficients, const Vec3& d) {
  const ShBasis y = sh_basis(d);
  Color sum;
  for (std::size_t k = 0; k < 9; ++k) sum += coefficients[k] * y[k];
  return max(sum, Color());
}

// The irradiance at a surface facing n of the radiance the coefficients hold, clamped at 0.
inline Color sh_irradiance(const ShColor& radiance, const Vec3& n) {
  const ShBasis y = sh_basis(n);
  Color sum;
  for (std::size_t k = 0; k < 9; ++k) sum += radiance[k] * (kClampedCosineBands[k] * y[k]);
  return max(sum, Color());
}

}  // namespace candela
