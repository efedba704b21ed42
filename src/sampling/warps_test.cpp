// The warps of warps.h: exact inverses both ways, a χ² test of each warp against its density,
// and each density integrating to 1 over its domain.
#include "sampling/warps.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "chi_square.h"
#include "math/constants.h"

namespace candela {
namespace {

// χ² tests in this file (Šidák correction of the 1% level).
constexpr int kWarpChiSquareTests = 14;
const double kWarpSignificance = test::sidak_significance(0.01, kWarpChiSquareTests);
constexpr int kWarpSamples = 100000;

// A grid of points strictly inside the unit square (never on the seams u = 0.5 or the edges).
std::vector<Vec2> square_grid(int n = 33) {
  std::vector<Vec2> points;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) points.push_back({(i + 0.5) / n, (j + 0.5) / n});
  return points;
}

// Unit directions on a (θ, φ) grid with θ in (theta_min, theta_max).
std::vector<Vec3> direction_grid(double theta_min, double theta_max, int n = 25) {
  std::vector<Vec3> directions;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double theta = theta_min + (theta_max - theta_min) * (i + 0.5) / n;
      const double phi = 2 * kPi * (j + 0.5) / n;
      directions.push_back(
          {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)});
    }
  return directions;
}

using DirectionWarp = std::function<Vec3(const Vec2&)>;
using DirectionInverse = std::function<Vec2(const Vec3&)>;

void expect_direction_round_trips(const DirectionWarp& warp, const DirectionInverse& inverse,
                                  double theta_max, double tolerance = 1e-9) {
  for (const Vec2& u : square_grid()) {
    const Vec3 w = warp(u);
    ASSERT_NEAR(length(w), 1.0, 1e-12) << u.x << ", " << u.y;
    const Vec2 back = inverse(w);
    EXPECT_NEAR(back.x, u.x, tolerance) << u.x << ", " << u.y;
    EXPECT_NEAR(back.y, u.y, tolerance) << u.x << ", " << u.y;
  }
  for (const Vec3& w : direction_grid(0, theta_max)) {
    const Vec3 again = warp(inverse(w));
    EXPECT_NEAR(again.x, w.x, tolerance) << w;
    EXPECT_NEAR(again.y, w.y, tolerance) << w;
    EXPECT_NEAR(again.z, w.z, tolerance) << w;
  }
}

void expect_direction_chi_square(const DirectionWarp& warp, const test::DirectionPdf& pdf, double theta_max,
                                 uint64_t seed) {
  test::SphereGrid grid;
  grid.theta_max = theta_max;
  const auto result = test::sphere_chi_square(
      [&](Pcg32& rng, Vec3& w) {
        const double u0 = rng.next_double();
        w = warp({u0, rng.next_double()});
        return true;
      },
      pdf, kWarpSamples, seed, grid);
  EXPECT_GT(result.p_value, kWarpSignificance) << result.message;
  // The p-values land in the XML report (--gtest_output=xml), one per seed.
  testing::Test::RecordProperty("p_value_seed_" + std::to_string(seed), std::to_string(result.p_value));
}

void expect_integrates_to_one(const test::DirectionPdf& pdf, double theta_max) {
  test::SphereGrid grid;
  grid.theta_max = theta_max;
  grid.theta_bins = 64;
  grid.phi_bins = 16;
  EXPECT_NEAR(test::integrate_over_sphere(pdf, grid), 1.0, 1e-4);
}

constexpr double kHalfPi = kPi / 2;

TEST(Warps, ConcentricDiscRoundTripsAndStaysInside) {
  for (const Vec2& u : square_grid()) {
    const Vec2 p = square_to_uniform_disc_concentric(u);
    EXPECT_LE(p.x * p.x + p.y * p.y, 1 + 1e-12);
    const Vec2 back = uniform_disc_concentric_to_square(p);
    EXPECT_NEAR(back.x, u.x, 1e-12);
    EXPECT_NEAR(back.y, u.y, 1e-12);
  }
  for (int i = 0; i < 20; ++i)
    for (int j = 0; j < 20; ++j) {
      const double r = (i + 0.5) / 20, phi = 2 * kPi * (j + 0.5) / 20;
      const Vec2 p{r * std::cos(phi), r * std::sin(phi)};
      const Vec2 again = square_to_uniform_disc_concentric(uniform_disc_concentric_to_square(p));
      EXPECT_NEAR(again.x, p.x, 1e-12);
      EXPECT_NEAR(again.y, p.y, 1e-12);
    }
  const Vec2 centre = square_to_uniform_disc_concentric({0.5, 0.5});
  EXPECT_EQ(centre.x, 0.0);
  EXPECT_EQ(centre.y, 0.0);
}

TEST(Warps, ConcentricDiscChiSquare) {
  // In polar coordinates (r², φ/2π) a uniform disc is uniform on the unit square with density
  // uniform_disc_pdf()·π (dA = π d(r²) d(φ/2π)), which keeps the disc's edge off the cells.
  const auto result = test::rectangle_chi_square(
      [](Pcg32& rng, Vec2& q) {
        const double u0 = rng.next_double();
        const Vec2 p = square_to_uniform_disc_concentric({u0, rng.next_double()});
        double phi = std::atan2(p.y, p.x) / (2 * kPi);
        if (phi < 0) phi += 1;
        q = {p.x * p.x + p.y * p.y, phi};
        return true;
      },
      [](const Vec2&) { return uniform_disc_pdf() * kPi; }, kWarpSamples, 1);
  EXPECT_GT(result.p_value, kWarpSignificance) << result.message;
  testing::Test::RecordProperty("p_value_seed_1", std::to_string(result.p_value));
  // ∫∫ pdf r dr dφ over the disc.
  test::RectangleGrid polar{0, 1, 0, 2 * kPi, 8, 8, 4};
  EXPECT_NEAR(test::integrate_over_rectangle([](const Vec2& q) { return uniform_disc_pdf() * q.x; }, polar),
              1.0, 1e-12);
}

TEST(Warps, UniformSphere) {
  expect_direction_round_trips(square_to_uniform_sphere, uniform_sphere_to_square, kPi);
  expect_direction_chi_square(
      square_to_uniform_sphere, [](const Vec3&) { return uniform_sphere_pdf(); }, kPi, 2);
  expect_integrates_to_one([](const Vec3&) { return uniform_sphere_pdf(); }, kPi);
}

TEST(Warps, UniformHemisphere) {
  expect_direction_round_trips(square_to_uniform_hemisphere, uniform_hemisphere_to_square, kHalfPi);
  expect_direction_chi_square(square_to_uniform_hemisphere, uniform_hemisphere_pdf, kHalfPi, 3);
  expect_integrates_to_one(uniform_hemisphere_pdf, kHalfPi);
  EXPECT_EQ(uniform_hemisphere_pdf({0, 0, -1}), 0.0);
}

TEST(Warps, CosineHemisphere) {
  expect_direction_round_trips(square_to_cosine_hemisphere, cosine_hemisphere_to_square, kHalfPi);
  expect_direction_chi_square(square_to_cosine_hemisphere, cosine_hemisphere_pdf, kHalfPi, 4);
  expect_integrates_to_one(cosine_hemisphere_pdf, kHalfPi);
  EXPECT_EQ(cosine_hemisphere_pdf({0, 0.6, -0.8}), 0.0);
}

TEST(Warps, UniformCone) {
  const double cos_max = 0.5;  // θ_max = π/3
  const double theta_max = std::acos(cos_max);
  const auto warp = [&](const Vec2& u) { return square_to_uniform_cone(u, cos_max); };
  const auto inverse = [&](const Vec3& w) { return uniform_cone_to_square(w, cos_max); };
  const auto pdf = [&](const Vec3& w) { return uniform_cone_pdf(w, cos_max); };
  expect_direction_round_trips(warp, inverse, theta_max);
  for (const Vec2& u : square_grid()) EXPECT_GE(warp(u).z, cos_max - 1e-15);
  expect_direction_chi_square(warp, pdf, theta_max + 1e-9, 5);
  // The pdf is the constant 1/(2π(1 − cos_max)) inside; integrate a hair inside the edge.
  expect_integrates_to_one(pdf, theta_max * (1 - 1e-12));
  EXPECT_EQ(uniform_cone_pdf({0, std::sin(1.1), std::cos(1.1)}, cos_max), 0.0);
}

TEST(Warps, PowerCosine) {
  uint64_t seed = 6;
  for (const double exponent : {0.0, 1.0, 10.0, 100.0}) {
    SCOPED_TRACE(exponent);
    const auto warp = [&](const Vec2& u) { return square_to_power_cosine(u, exponent); };
    const auto inverse = [&](const Vec3& w) { return power_cosine_to_square(w, exponent); };
    const auto pdf = [&](const Vec3& w) { return power_cosine_pdf(w, exponent); };
    expect_direction_round_trips(warp, inverse, exponent > 50 ? 0.5 : kHalfPi, 1e-8);
    if (exponent > 0) expect_direction_chi_square(warp, pdf, kHalfPi, seed++);
    expect_integrates_to_one(pdf, kHalfPi);
  }
}

TEST(Warps, Beckmann) {
  uint64_t seed = 20;
  for (const double alpha : {0.1, 0.5, 1.0}) {
    SCOPED_TRACE(alpha);
    const auto warp = [&](const Vec2& u) { return square_to_beckmann(u, alpha); };
    const auto inverse = [&](const Vec3& m) { return beckmann_to_square(m, alpha); };
    const auto pdf = [&](const Vec3& m) { return beckmann_pdf(m, alpha); };
    // Far out the cdf 1 − exp(−tan²θ/α²) is 1 to within rounding: the inverse is checked inside.
    expect_direction_round_trips(warp, inverse, std::atan(3 * alpha), 1e-8);
    if (alpha < 1) expect_direction_chi_square(warp, pdf, kHalfPi, seed++);
    expect_integrates_to_one(pdf, kHalfPi);
  }
}

TEST(Warps, Ggx) {
  uint64_t seed = 30;
  for (const double alpha : {0.1, 0.5, 1.0}) {
    SCOPED_TRACE(alpha);
    const auto warp = [&](const Vec2& u) { return square_to_ggx(u, alpha); };
    const auto inverse = [&](const Vec3& m) { return ggx_to_square(m, alpha); };
    const auto pdf = [&](const Vec3& m) { return ggx_pdf(m, alpha); };
    expect_direction_round_trips(warp, inverse, std::atan(20 * alpha), 1e-8);
    if (alpha < 1) expect_direction_chi_square(warp, pdf, kHalfPi, seed++);
    // GGX's tail is long (∝ cos θ near the horizon): a finer grid near the pole of sharp lobes.
    test::SphereGrid grid;
    grid.theta_max = kHalfPi;
    grid.theta_bins = 256;
    grid.phi_bins = 4;
    EXPECT_NEAR(test::integrate_over_sphere(pdf, grid), 1.0, 1e-4);
  }
}

TEST(Warps, MicrofacetDensitiesAreDCosTheta) {
  // At the pole D = 1/(πα²) for both distributions.
  for (const double alpha : {0.2, 0.7}) {
    EXPECT_NEAR(beckmann_pdf({0, 0, 1}, alpha), 1 / (kPi * alpha * alpha), 1e-12);
    EXPECT_NEAR(ggx_pdf({0, 0, 1}, alpha), 1 / (kPi * alpha * alpha), 1e-12);
  }
  EXPECT_EQ(beckmann_pdf({0, 0, -1}, 0.3), 0.0);
  EXPECT_EQ(ggx_pdf({1, 0, 0}, 0.3), 0.0);
}

TEST(Warps, TriangleRoundTripsAndStaysInside) {
  for (const Vec2& u : square_grid()) {
    const Vec2 b = square_to_uniform_triangle(u);
    EXPECT_GE(b.x, 0.0);
    EXPECT_GE(b.y, 0.0);
    EXPECT_LE(b.x + b.y, 1.0 + 1e-15);
    const Vec2 back = uniform_triangle_to_square(b);
    EXPECT_NEAR(back.x, u.x, 1e-15);
    EXPECT_NEAR(back.y, u.y, 1e-15);
  }
  for (int i = 0; i < 30; ++i)
    for (int j = 0; i + j < 29; ++j) {
      const Vec2 b{(i + 0.3) / 30, (j + 0.6) / 30};
      const Vec2 again = square_to_uniform_triangle(uniform_triangle_to_square(b));
      EXPECT_NEAR(again.x, b.x, 1e-15);
      EXPECT_NEAR(again.y, b.y, 1e-15);
    }
}

TEST(Warps, TriangleChiSquare) {
  // Uniform barycentrics map to uniform points of the square under the inverse of the other
  // classic triangle map (b0 = 1 − √u, b1 = v√u), whose inverse is u = (1 − b0)², v = b1/(1 − b0):
  // an independent check with density 1 and no edge inside the cells.
  const auto result = test::rectangle_chi_square(
      [](Pcg32& rng, Vec2& q) {
        const double u0 = rng.next_double();
        const Vec2 b = square_to_uniform_triangle({u0, rng.next_double()});
        const double rest = 1 - b.x;
        q = {rest * rest, rest > 0 ? b.y / rest : 0.0};
        return true;
      },
      [](const Vec2&) { return 1.0; }, kWarpSamples, 40);
  EXPECT_GT(result.p_value, kWarpSignificance) << result.message;
  testing::Test::RecordProperty("p_value_seed_40", std::to_string(result.p_value));
}

TEST(Warps, LinearAndBilinearRoundTripAndIntegrateToOne) {
  for (const auto& [a, b] :
       {std::pair{1.0, 1.0}, std::pair{0.0, 3.0}, std::pair{5.0, 0.1}, std::pair{2.0, 2.0 + 1e-12}})
    for (int i = 0; i <= 20; ++i) {
      const double u = i / 20.0;
      const double x = sample_linear(u, a, b);
      EXPECT_GE(x, 0);
      EXPECT_LT(x, 1);
      EXPECT_NEAR(linear_to_square(x, a, b), u, 1e-12) << a << " " << b << " " << u;
    }
  const double weights[][4] = {{1, 1, 1, 1}, {1, 4, 0.5, 9}, {0, 1, 0, 0}, {1e-3, 2, 3, 0.2}};
  for (const auto& w : weights) {
    double integral = 0;
    for (const Vec2& p : square_grid(200)) integral += bilinear_pdf(p, w) / (200.0 * 200.0);
    EXPECT_NEAR(integral, 1, 1e-9);
    for (const Vec2& u : square_grid()) {
      const Vec2 p = square_to_bilinear(u, w);
      const Vec2 back = bilinear_to_square(p, w);
      EXPECT_NEAR(back.x, u.x, 1e-9);
      EXPECT_NEAR(back.y, u.y, 1e-9);
    }
  }
}

TEST(Warps, BilinearChiSquare) {
  const double w[4] = {0.2, 3, 1, 6};
  const auto result = test::rectangle_chi_square(
      [&](Pcg32& rng, Vec2& q) {
        const double u0 = rng.next_double();
        q = square_to_bilinear({u0, rng.next_double()}, w);
        return true;
      },
      [&](const Vec2& p) { return bilinear_pdf(p, w); }, kWarpSamples, 41);
  EXPECT_GT(result.p_value, kWarpSignificance) << result.message;
  testing::Test::RecordProperty("p_value_seed_41", std::to_string(result.p_value));
}

// The harness itself: the incomplete gamma against known values, and a biased sampler fails.
TEST(ChiSquare, PValuesOfKnownQuantiles) {
  EXPECT_NEAR(test::chi_square_p_value(3.841458820694124, 1), 0.05, 1e-9);
  EXPECT_NEAR(test::chi_square_p_value(18.307038053275146, 10), 0.05, 1e-9);
  EXPECT_NEAR(test::chi_square_p_value(135.8067, 100), 0.01, 1e-5);
  EXPECT_NEAR(test::chi_square_p_value(2, 2), std::exp(-1.0), 1e-12);  // χ²(2) is exponential
  EXPECT_NEAR(test::sidak_significance(0.01, 1), 0.01, 1e-15);
  EXPECT_LT(test::sidak_significance(0.01, 10), 0.001006);
}

TEST(ChiSquare, RejectsAWrongDensity) {
  // Cosine-distributed samples tested against the uniform hemisphere: must fail clearly.
  test::SphereGrid grid;
  grid.theta_max = kHalfPi;
  const auto result = test::sphere_chi_square(
      [](Pcg32& rng, Vec3& w) {
        const double u0 = rng.next_double();
        w = square_to_cosine_hemisphere({u0, rng.next_double()});
        return true;
      },
      uniform_hemisphere_pdf, 20000, 7, grid);
  EXPECT_LT(result.p_value, 1e-6) << result.message;
  // Samples where the density is zero fail outright.
  const auto leak = test::sphere_chi_square(
      [](Pcg32& rng, Vec3& w) {
        w = square_to_uniform_sphere({rng.next_double(), rng.next_double()});
        return true;
      },
      uniform_hemisphere_pdf, 1000, 8);
  EXPECT_EQ(leak.p_value, 0.0) << leak.message;
}

}  // namespace
}  // namespace candela
