// Tests of the band-2 spherical harmonics hierarchical radiosity's clusters use
// (math/spherical_harmonics.h).
#include "math/spherical_harmonics.h"

#include <gtest/gtest.h>

#include <cmath>

namespace candela {
namespace {

const Vec3 kDirections[] = {Vec3(0, 0, 1), Vec3(1, 0, 0), Vec3(0, -1, 0), normalize(Vec3(1, 2, -3)),
                            normalize(Vec3(-0.3, 0.1, 0.9))};

// The basis is orthonormal: a Monte Carlo-free check by a fine latitude–longitude quadrature.
TEST(SphericalHarmonics, BasisIsOrthonormalOverTheSphere) {
  const int rings = 200, sectors = 400;
  double gram[9][9] = {};
  for (int i = 0; i < rings; ++i) {
    const double theta = kPi * (i + 0.5) / rings;
    const double weight = std::sin(theta) * (kPi / rings) * (2 * kPi / sectors);
    for (int j = 0; j < sectors; ++j) {
      const double phi = 2 * kPi * (j + 0.5) / sectors;
      const ShBasis y =
          sh_basis(Vec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)));
      for (int a = 0; a < 9; ++a)
        for (int b = 0; b < 9; ++b) gram[a][b] += y[a] * y[b] * weight;
    }
  }
  for (int a = 0; a < 9; ++a)
    for (int b = 0; b < 9; ++b) EXPECT_NEAR(gram[a][b], a == b ? 1.0 : 0.0, 1e-4) << a << ", " << b;
}

// A uniform radiance L gives the irradiance πL whatever the normal (exact: band 0 only).
TEST(SphericalHarmonics, UniformRadianceGivesPiLAtEveryNormal) {
  ShColor radiance{};
  radiance[0] = Color(2.0 * std::sqrt(4 * kPi));  // L = 2: L_00 = L / Y_00
  for (const Vec3& n : kDirections) EXPECT_NEAR(sh_irradiance(radiance, n).g, 2 * kPi, 1e-12);
}

// A clamped cosine lobe keeps its integral, π × the weight (band 0 carries it), and its series is
// largest along its normal and near the truncation's known values elsewhere (Ramamoorthi and
// Hanrahan: 1/4 + 1/2 + 5/16 = 1.0625 along n, 1/4 − 5/32 at 90°).
TEST(SphericalHarmonics, ClampedCosineKeepsItsPowerAndShape) {
  for (const Vec3& n : kDirections) {
    ShColor lobe{};
    add_clamped_cosine(lobe, n, Color(3));
    EXPECT_NEAR(lobe[0].r * std::sqrt(4 * kPi), 3 * kPi, 1e-12);
    EXPECT_NEAR(sh_evaluate(lobe, n).r, 3 * 1.0625, 1e-9);
    const Vec3 side = normalize(cross(n, std::fabs(n.x) < 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0)));
    EXPECT_NEAR(sh_evaluate(lobe, side).r, 3 * (0.25 - 5.0 / 32), 1e-9);
    EXPECT_NEAR(sh_evaluate(lobe, -n).r, 3 * (0.25 - 0.5 + 5.0 / 16), 1e-9);  // 0.0625: the ringing
  }
}

// Light from one direction: the irradiance follows the cosine within the band-2 truncation's error.
TEST(SphericalHarmonics, DeltaLightFollowsTheCosine) {
  const Vec3 from = normalize(Vec3(0.2, 0.3, 1));
  ShColor radiance{};
  add_delta(radiance, from, Color(1));
  for (const Vec3& n : kDirections) {
    const double exact = std::max(0.0, dot(n, from));
    EXPECT_NEAR(sh_irradiance(radiance, n).b, exact, 0.1) << n.x << " " << n.y << " " << n.z;
  }
}

}  // namespace
}  // namespace candela
