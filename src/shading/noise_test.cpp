#include "shading/noise.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "math/pcg32.h"
#include "shape_test_support.h"

namespace candela {
namespace {

TEST(Noise, IsZeroAtEveryLatticePoint) {
  // Each corner's ramp g · (p − corner) vanishes at its corner, and the fade weights pick that
  // corner alone there.
  for (int x = -6; x <= 6; ++x)
    for (int y = -6; y <= 6; ++y)
      for (int z = -6; z <= 6; ++z) EXPECT_EQ(gradient_noise({x * 1.0, y * 1.0, z * 1.0}), 0.0);
  EXPECT_EQ(gradient_noise({1e6, -3e7, 255}), 0.0);
}

TEST(Noise, StaysWithinAboutPlusMinusOne) {
  Pcg32 rng(7, 1);
  double lowest = 0, highest = 0;
  for (int i = 0; i < 100000; ++i) {
    const double n = gradient_noise(testing::random_point(rng, 300));
    lowest = std::min(lowest, n);
    highest = std::max(highest, n);
  }
  EXPECT_GE(lowest, -1.05);
  EXPECT_LE(highest, 1.05);
  // And it is not degenerate: the samples reach well into both halves of the range.
  EXPECT_LT(lowest, -0.6);
  EXPECT_GT(highest, 0.6);
}

TEST(Noise, AnalyticGradientMatchesCentralDifferences) {
  Pcg32 rng(11, 2);
  const double h = 1e-5;
  for (int i = 0; i < 2000; ++i) {
    const Vec3 p = testing::random_point(rng, 40);
    const Vec3 gradient = gradient_noise_gradient(p);
    for (int axis = 0; axis < 3; ++axis) {
      Vec3 forward = p, backward = p;
      forward[axis] += h;
      backward[axis] -= h;
      const double difference = (gradient_noise(forward) - gradient_noise(backward)) / (2 * h);
      // Central differences err by O(h²·f''') ≈ 1e-9 here, plus rounding ≈ 1e-16/h.
      EXPECT_NEAR(gradient[axis], difference, 1e-6 * std::max(1.0, std::fabs(difference)))
          << "at " << p << " axis " << axis;
    }
  }
}

TEST(Noise, SampleCarriesTheSameValueAsGradientNoise) {
  Pcg32 rng(5, 3);
  for (int i = 0; i < 1000; ++i) {
    const Vec3 p = testing::random_point(rng, 100);
    const NoiseSample sample = gradient_noise_sample(p);
    EXPECT_EQ(sample.value, gradient_noise(p));
    EXPECT_EQ(sample.gradient, gradient_noise_gradient(p));
  }
}

TEST(Noise, IsC1AcrossACellFace) {
  // Just left and just right of the face x = 3 the value and the whole gradient agree: the
  // quintic fade has zero slope at the face, so the neighbouring cells meet smoothly.
  const double eps = 1e-9;
  for (double y : {0.1, 0.37, 0.8})
    for (double z : {-2.3, 0.5, 4.71}) {
      const Vec3 left{3 - eps, y, z}, right{3 + eps, y, z};
      EXPECT_NEAR(gradient_noise(left), gradient_noise(right), 1e-8);
      const Vec3 gl = gradient_noise_gradient(left), gr = gradient_noise_gradient(right);
      EXPECT_NEAR(gl.x, gr.x, 1e-7);
      EXPECT_NEAR(gl.y, gr.y, 1e-7);
      EXPECT_NEAR(gl.z, gr.z, 1e-7);
    }
}

TEST(Noise, MatchesPerlinsReferenceAtTheCellCentre) {
  // Worked by hand from ImprovedNoise.java (Perlin 2002). At (0.5, 0.5, 0.5) every fade weight is
  // 1/2, so the noise is the mean of the eight corner ramps g · (p − corner), p − corner = (±½)³.
  // Hash chain from X = Y = Z = 0: A = p[0] = 151, AA = p[151] = 17, AB = p[152] = 182;
  // B = p[1] = 160, BA = p[160] = 119, BB = p[161] = 248. The corner hashes p[..] & 15 and the
  // gradients the reference's grad() uses for them:
  //   000: p[17]  = 36  → 4  (1,0,1)   · ( ½, ½, ½) =  1
  //   100: p[119] = 86  → 6  (1,0,−1)  · (−½, ½, ½) = −1
  //   010: p[182] = 108 → 12 (1,1,0)   · ( ½,−½, ½) =  0
  //   110: p[248] = 128 → 0  (1,1,0)   · (−½,−½, ½) = −1
  //   001: p[18]  = 103 → 7  (−1,0,−1) · ( ½, ½,−½) =  0
  //   101: p[120] = 164 → 4  (1,0,1)   · (−½, ½,−½) = −1
  //   011: p[183] = 110 → 14 (−1,1,0)  · ( ½,−½,−½) = −1
  //   111: p[249] = 195 → 3  (−1,−1,0) · (−½,−½,−½) =  1
  // Sum −2, mean −1/4. A wrong entry in the permutation or the gradient table changes it.
  EXPECT_EQ(gradient_noise({0.5, 0.5, 0.5}), -0.25);
}

TEST(Noise, GoldenValues) {
  // Values of ImprovedNoise.noise(x, y, z) (a literal transliteration of Perlin's Java code, run
  // in double precision), which this implementation reproduces; they pin down the hash chain
  // for negative and large cell indices too.
  EXPECT_NEAR(gradient_noise({3.14, 42.0, 7.0}), 0.13691995878400012, 1e-12);
  EXPECT_NEAR(gradient_noise({-1.25, 2.5, 0.75}), -0.16121816635131836, 1e-12);
  EXPECT_NEAR(gradient_noise({123.456, -78.9, 0.001}), 0.09044436761007818, 1e-12);
  EXPECT_NEAR(gradient_noise({3.7, 1.2, -4.6}), -0.30739261905960963, 1e-12);
}

TEST(Noise, RepeatsWithPeriod256) {
  // The lattice index wraps modulo 256 (the permutation's length).
  const Vec3 p{0.3, 1.7, -2.2};
  EXPECT_NEAR(gradient_noise(p), gradient_noise(p + Vec3{256, -512, 1024}), 1e-12);
}

TEST(Noise, FractalNoiseWithOneOctaveIsTheNoise) {
  Pcg32 rng(3, 4);
  for (int i = 0; i < 100; ++i) {
    const Vec3 p = testing::random_point(rng, 20);
    EXPECT_EQ(fractal_noise(p, 1), gradient_noise(p));
    EXPECT_EQ(turbulence(p, 1), std::fabs(gradient_noise(p)));
  }
}

TEST(Noise, FractalNoiseSumsScaledOctaves) {
  const Vec3 p{0.61, -1.3, 2.27};
  const double expected = gradient_noise(p) + 0.4 * gradient_noise(p * 3) + 0.16 * gradient_noise(p * 9);
  EXPECT_NEAR(fractal_noise(p, 3, 3, 0.4), expected, 1e-15);
  const double expected_turbulence = std::fabs(gradient_noise(p)) + 0.5 * std::fabs(gradient_noise(p * 2)) +
                                     0.25 * std::fabs(gradient_noise(p * 4));
  EXPECT_NEAR(turbulence(p, 3), expected_turbulence, 1e-15);
  EXPECT_EQ(fractal_noise(p, 0), 0.0);
}

TEST(Noise, FractalGradientMatchesCentralDifferences) {
  Pcg32 rng(13, 5);
  const double h = 1e-6;
  for (int i = 0; i < 200; ++i) {
    const Vec3 p = testing::random_point(rng, 10);
    const Vec3 gradient = fractal_noise_gradient(p, 4);
    for (int axis = 0; axis < 3; ++axis) {
      Vec3 forward = p, backward = p;
      forward[axis] += h;
      backward[axis] -= h;
      const double difference = (fractal_noise(forward, 4) - fractal_noise(backward, 4)) / (2 * h);
      EXPECT_NEAR(gradient[axis], difference, 1e-6 * std::max(1.0, std::fabs(difference)));
    }
  }
}

TEST(Noise, TurbulenceIsNonNegative) {
  Pcg32 rng(17, 6);
  for (int i = 0; i < 10000; ++i) EXPECT_GE(turbulence(testing::random_point(rng, 50), 5), 0.0);
}

TEST(Noise, HugeCoordinatesStayFiniteAndBounded) {
  for (double big : {1e9, -1e9, 123456789.123, 0x1p52 + 0.5, 1e18, -1e300, 1.7e308}) {
    const Vec3 p{big, 0.5 * big, -0.25};
    const double n = gradient_noise(p);
    EXPECT_TRUE(std::isfinite(n)) << big;
    EXPECT_LE(std::fabs(n), 1.05) << big;
    EXPECT_TRUE(is_finite(gradient_noise_gradient(p))) << big;
    EXPECT_TRUE(std::isfinite(fractal_noise(p, 8))) << big;
    EXPECT_TRUE(std::isfinite(turbulence(p, 8))) << big;
  }
  // Still the same function out there: near 1e9 it is zero on the lattice and varies between.
  EXPECT_EQ(gradient_noise({1e9, 1e9 + 1, -1e9}), 0.0);
  EXPECT_NE(gradient_noise({1e9 + 0.5, 1e9 + 0.25, 0.5}), 0.0);
}

TEST(Noise, NonFiniteInputGivesZero) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (const Vec3& p : {Vec3{nan, 0.5, 0.5}, Vec3{0.5, nan, nan}, Vec3{inf, 0, 0}, Vec3{0, 0, -inf}}) {
    EXPECT_EQ(gradient_noise(p), 0.0);
    EXPECT_EQ(gradient_noise_gradient(p), Vec3());
    EXPECT_EQ(fractal_noise(p, 6), 0.0);
    EXPECT_EQ(turbulence(p, 6), 0.0);
  }
}

}  // namespace
}  // namespace candela
