#include "math/polynomial.h"

#include <gtest/gtest.h>

#include <cmath>

namespace candela {
namespace {

TEST(Polynomial, QuadraticDistinctRootsAscending) {
  double roots[2];
  ASSERT_EQ(solve_quadratic(1, -3, 2, roots), 2);
  EXPECT_DOUBLE_EQ(roots[0], 1.0);
  EXPECT_DOUBLE_EQ(roots[1], 2.0);
  ASSERT_EQ(solve_quadratic(-2, 0, 8, roots), 2);  // -2 (x - 2)(x + 2)
  EXPECT_DOUBLE_EQ(roots[0], -2.0);
  EXPECT_DOUBLE_EQ(roots[1], 2.0);
}

TEST(Polynomial, QuadraticDoubleRootIsReportedTwice) {
  double roots[2];
  ASSERT_EQ(solve_quadratic(1, -2, 1, roots), 2);
  EXPECT_DOUBLE_EQ(roots[0], 1.0);
  EXPECT_DOUBLE_EQ(roots[1], 1.0);
}

TEST(Polynomial, QuadraticWithoutRealRoots) {
  double roots[2];
  EXPECT_EQ(solve_quadratic(1, 0, 1, roots), 0);
  EXPECT_EQ(solve_quadratic(0, 0, 1, roots), 0);  // constant
}

TEST(Polynomial, QuadraticDegeneratesToLinear) {
  double roots[2];
  ASSERT_EQ(solve_quadratic(0, 2, -4, roots), 1);
  EXPECT_DOUBLE_EQ(roots[0], 2.0);
}

TEST(Polynomial, QuadraticSmallRootWithoutCancellation) {
  // x^2 - 1e8 x + 1: roots 1e8 and 1e-8 to 16 digits (their product is 1); the naive formula
  // (-b - sqrt(b^2 - 4c)) / 2 loses the small one entirely.
  double roots[2];
  ASSERT_EQ(solve_quadratic(1, -1e8, 1, roots), 2);
  EXPECT_NEAR(roots[0], 1e-8, 1e-22);
  EXPECT_NEAR(roots[1], 1e8, 1e-6);
}

TEST(Polynomial, CubicThreeRealRoots) {
  double roots[3];
  ASSERT_EQ(solve_cubic(1, -6, 11, -6, roots), 3);  // (x-1)(x-2)(x-3)
  EXPECT_NEAR(roots[0], 1.0, 1e-14);
  EXPECT_NEAR(roots[1], 2.0, 1e-14);
  EXPECT_NEAR(roots[2], 3.0, 1e-14);
  // 2 (x + 1)(x - 0.5)(x - 4) = 2x^3 - 7x^2 - 5x + 4.
  ASSERT_EQ(solve_cubic(2, -7, -5, 4, roots), 3);
  EXPECT_NEAR(roots[0], -1.0, 1e-14);
  EXPECT_NEAR(roots[1], 0.5, 1e-14);
  EXPECT_NEAR(roots[2], 4.0, 1e-14);
}

TEST(Polynomial, CubicOneRealRoot) {
  double roots[3];
  ASSERT_EQ(solve_cubic(1, -2, 1, -2, roots), 1);  // (x - 2)(x^2 + 1)
  EXPECT_NEAR(roots[0], 2.0, 1e-14);
}

TEST(Polynomial, CubicDoubleAndTripleRoots) {
  double roots[3];
  ASSERT_EQ(solve_cubic(1, 0, -3, 2, roots), 3);  // (x - 1)^2 (x + 2)
  EXPECT_NEAR(roots[0], -2.0, 1e-14);
  EXPECT_NEAR(roots[1], 1.0, 1e-7);
  EXPECT_NEAR(roots[2], 1.0, 1e-7);
  ASSERT_EQ(solve_cubic(1, -3, 3, -1, roots), 3);  // (x - 1)^3
  for (const double root : roots) EXPECT_NEAR(root, 1.0, 1e-5);
}

TEST(Polynomial, QuarticFourDistinctRoots) {
  double roots[4];
  ASSERT_EQ(solve_quartic(1, -10, 35, -50, 24, roots), 4);  // (x-1)(x-2)(x-3)(x-4)
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(roots[i], i + 1.0, 1e-13);
  // 3 (x + 2)(x + 0.5)(x - 0.25)(x - 8): leading coefficient != 1, mixed signs.
  // (x + 2)(x + 0.5) = x^2 + 2.5x + 1; (x - 0.25)(x - 8) = x^2 - 8.25x + 2;
  // product: x^4 - 5.75x^3 - 17.625x^2 - 3.25x + 2.
  ASSERT_EQ(solve_quartic(3, -17.25, -52.875, -9.75, 6, roots), 4);
  EXPECT_NEAR(roots[0], -2.0, 1e-13);
  EXPECT_NEAR(roots[1], -0.5, 1e-13);
  EXPECT_NEAR(roots[2], 0.25, 1e-13);
  EXPECT_NEAR(roots[3], 8.0, 1e-13);
}

TEST(Polynomial, QuarticSymmetricRoots) {
  // Roots symmetric about their mean make the depressed quartic biquadratic (q = 0), as for a
  // ray through the centre of a torus: (y^2 - 4)(y^2 - 16) shifted by 5.
  // (x - 1)(x - 3)(x - 7)(x - 9) = (x^2 - 10x + 9)(x^2 - 10x + 21)
  //   = x^4 - 20x^3 + 130x^2 - 300x + 189.
  double roots[4];
  ASSERT_EQ(solve_quartic(1, -20, 130, -300, 189, roots), 4);
  EXPECT_NEAR(roots[0], 1.0, 1e-12);
  EXPECT_NEAR(roots[1], 3.0, 1e-12);
  EXPECT_NEAR(roots[2], 7.0, 1e-12);
  EXPECT_NEAR(roots[3], 9.0, 1e-12);
}

TEST(Polynomial, QuarticTwoRealRoots) {
  double roots[4];
  ASSERT_EQ(solve_quartic(1, 1, -1, 1, -2, roots), 2);  // (x - 1)(x + 2)(x^2 + 1)
  EXPECT_NEAR(roots[0], -2.0, 1e-13);
  EXPECT_NEAR(roots[1], 1.0, 1e-13);
}

TEST(Polynomial, QuarticWithoutRealRoots) {
  double roots[4];
  EXPECT_EQ(solve_quartic(1, 0, 5, 0, 4, roots), 0);    // (x^2 + 1)(x^2 + 4)
  EXPECT_EQ(solve_quartic(1, 0, 3, -6, 10, roots), 0);  // (x^2 + 2x + 5)(x^2 - 2x + 2)
}

TEST(Polynomial, QuarticDoubleRoots) {
  // A double root (a tangent ray) is reported twice, to about sqrt(epsilon).
  double roots[4];
  ASSERT_EQ(solve_quartic(1, -7, 17, -17, 6, roots), 4);  // (x - 1)^2 (x - 2)(x - 3)
  EXPECT_NEAR(roots[0], 1.0, 1e-7);
  EXPECT_NEAR(roots[1], 1.0, 1e-7);
  EXPECT_NEAR(roots[2], 2.0, 1e-12);
  EXPECT_NEAR(roots[3], 3.0, 1e-12);
  ASSERT_EQ(solve_quartic(1, 0, -8, 0, 16, roots), 4);  // (x^2 - 4)^2
  EXPECT_NEAR(roots[0], -2.0, 1e-7);
  EXPECT_NEAR(roots[1], -2.0, 1e-7);
  EXPECT_NEAR(roots[2], 2.0, 1e-7);
  EXPECT_NEAR(roots[3], 2.0, 1e-7);
}

TEST(Polynomial, QuarticWidelySpreadRoots) {
  // (x - 0.001)(x - 1)(x - 10)(x - 100), relative accuracy on every root.
  const double r[4] = {0.001, 1, 10, 100};
  const double e1 = r[0] + r[1] + r[2] + r[3];
  const double e2 = r[0] * r[1] + r[0] * r[2] + r[0] * r[3] + r[1] * r[2] + r[1] * r[3] + r[2] * r[3];
  const double e3 = r[0] * r[1] * r[2] + r[0] * r[1] * r[3] + r[0] * r[2] * r[3] + r[1] * r[2] * r[3];
  const double e4 = r[0] * r[1] * r[2] * r[3];
  double roots[4];
  ASSERT_EQ(solve_quartic(1, -e1, e2, -e3, e4, roots), 4);
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(roots[i], r[i], 1e-12 * r[i]);
}

TEST(Polynomial, QuarticDegeneratesToCubic) {
  double roots[4];
  ASSERT_EQ(solve_quartic(0, 1, -6, 11, -6, roots), 3);
  EXPECT_NEAR(roots[0], 1.0, 1e-14);
  EXPECT_NEAR(roots[2], 3.0, 1e-14);
}

}  // namespace
}  // namespace candela
