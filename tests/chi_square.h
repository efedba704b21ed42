// A χ² goodness-of-fit harness for sampling routines, after Mitsuba's and pbrt's (STYLE.md §5):
// draw N samples, histogram them over a grid, integrate the claimed density numerically over
// each cell (composite 3-point Gauss–Legendre on a sub-grid) for the expected counts, pool the cells expected
// to hold fewer than 5 samples, and compute the p-value of the χ² statistic. A test passes when
// p exceeds a significance level of 0.01 Šidák-corrected for the number of tests in the suite
// (sidak_significance). Two domains:
//   - the sphere of directions on a (θ, φ) grid, θ ∈ [0, theta_max] (solid-angle densities);
//   - a rectangle of the plane on an (x, y) grid (area densities: disc or triangle warps,
//     usually after a change of variables that makes the domain a rectangle).
// A sample that lands where the integrated density is zero fails the test outright. A sampler
// may decline (return false): those samples count nowhere, and the density should then
// integrate to the probability of success (a BSDF whose draws under the surface are rejected).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "math/pcg32.h"
#include "math/vector.h"

namespace candela::test {

struct ChiSquareResult {
  double statistic = 0;
  int degrees_of_freedom = 0;
  double p_value = 0;
  int pooled_cells = 0;  // cells merged because their expected count was below 5
  int accepted = 0;      // samples that the sampler produced
  double expected_total = 0;
  std::string message;  // a summary for the failure message: worst cells, totals
};

// Q(a, x) = Γ(a, x)/Γ(a), the regularized upper incomplete gamma function (series for
// x < a + 1, Lentz's continued fraction otherwise; Numerical Recipes §6.2).
double regularized_gamma_q(double a, double x);
// P(X² ≥ statistic) for X² ~ χ²(dof).
double chi_square_p_value(double statistic, int degrees_of_freedom);
// The per-test level that keeps the family-wise level α over test_count independent tests:
// 1 − (1 − α)^(1/test_count).
double sidak_significance(double alpha, int test_count);

// The test proper on observed and expected counts per cell (pooling cells with expected < 5).
ChiSquareResult chi_square_test(const std::vector<double>& observed, const std::vector<double>& expected,
                                double min_expected = 5);

// Directions: sample(rng, direction) returns false to decline; pdf in solid angle.
struct SphereGrid {
  int theta_bins = 16;
  int phi_bins = 32;
  double theta_max = 3.14159265358979323846;  // π/2 for hemispherical densities
  int subdivisions = 3;                       // Gauss–Legendre sub-intervals per cell side
};
using DirectionSampler = std::function<bool(Pcg32& rng, Vec3& direction)>;
using DirectionPdf = std::function<double(const Vec3& direction)>;
ChiSquareResult sphere_chi_square(const DirectionSampler& sample, const DirectionPdf& pdf, int sample_count,
                                  uint64_t seed, const SphereGrid& grid = {});
// ∫ pdf dω over the grid's part of the sphere (the same quadrature, cell by cell).
double integrate_over_sphere(const DirectionPdf& pdf, const SphereGrid& grid = {});

// Points of the rectangle [x0, x1) × [y0, y1); pdf in area.
struct RectangleGrid {
  double x0 = 0, x1 = 1, y0 = 0, y1 = 1;
  int x_bins = 20;
  int y_bins = 20;
  int subdivisions = 3;  // Gauss–Legendre sub-intervals per cell side
};
using PointSampler = std::function<bool(Pcg32& rng, Vec2& point)>;
using PointPdf = std::function<double(const Vec2& point)>;
ChiSquareResult rectangle_chi_square(const PointSampler& sample, const PointPdf& pdf, int sample_count,
                                     uint64_t seed, const RectangleGrid& grid = {});
double integrate_over_rectangle(const PointPdf& pdf, const RectangleGrid& grid = {});

}  // namespace candela::test
