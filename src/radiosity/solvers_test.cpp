#include "radiosity/solvers.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "math/constants.h"
#include "math/pcg32.h"
#include "radiosity/radiosity_system.h"

namespace candela {
namespace {

// ---- Test scenes -----------------------------------------------------------------------------

// The inside of a unit sphere cut into latitude bands (at the heights in z_cuts, from −1 to 1) and
// each band into sectors (fractions of the full turn, summing to 1): patch areas Δz·2π·fraction
// (Archimedes). Between any two regions of a sphere's inside F_ij = A_j / A_sphere, F_ii included:
// the exact form factors of a closed enclosure (every row sums to 1).
struct SpherePatches {
  std::vector<double> areas;
  Eigen::MatrixXd form_factors;
};

SpherePatches sphere_patches(const std::vector<double>& z_cuts, const std::vector<double>& sector_fractions) {
  SpherePatches sphere;
  for (std::size_t band = 0; band + 1 < z_cuts.size(); ++band) {
    for (const double fraction : sector_fractions) {
      sphere.areas.push_back((z_cuts[band + 1] - z_cuts[band]) * 2 * kPi * fraction);
    }
  }
  const auto n = static_cast<Eigen::Index>(sphere.areas.size());
  double total_area = 0;
  for (const double area : sphere.areas) total_area += area;
  sphere.form_factors.resize(n, n);
  for (Eigen::Index i = 0; i < n; ++i) {
    for (Eigen::Index j = 0; j < n; ++j) sphere.form_factors(i, j) = sphere.areas[j] / total_area;
  }
  return sphere;
}

// 8 bands of equal height × 6 equal sectors: 48 patches of area 4π/48.
SpherePatches equal_area_sphere() {
  std::vector<double> cuts;
  for (int k = 0; k <= 8; ++k) cuts.push_back(-1.0 + 2.0 * k / 8);
  return sphere_patches(cuts, std::vector<double>(6, 1.0 / 6));
}

// Bands and sectors of random sizes: 7 × 5 patches whose areas differ by up to two or three
// orders of magnitude.
SpherePatches unequal_area_sphere(uint64_t seed) {
  Pcg32 rng(seed, 1);
  std::vector<double> cuts = {-1.0, 1.0};
  for (int k = 0; k < 6; ++k) cuts.push_back(-1.0 + 2.0 * rng.next_double());
  std::sort(cuts.begin(), cuts.end());
  std::vector<double> fractions;
  double sum = 0;
  for (int k = 0; k < 5; ++k) {
    fractions.push_back(0.2 + rng.next_double());
    sum += fractions.back();
  }
  for (double& fraction : fractions) fraction /= sum;
  return sphere_patches(cuts, fractions);
}

RadiositySystem uniform_system(const std::vector<double>& areas, const Color& reflectance,
                               const Color& emission) {
  return {areas, std::vector<Color>(areas.size(), reflectance), std::vector<Color>(areas.size(), emission)};
}

// A random but physical system: F_ij = G_ij / A_i from a random symmetric non-negative "A_i F_ij"
// matrix G (some entries 0: occlusion) whose row sums are at most A_i, so that reciprocity
// A_i F_ij = A_j F_ji holds exactly and every row sums to at most 1 (the largest to exactly 1).
// Reflectances per channel in [0.2, 0.8]; three emitters.
struct PhysicalSystem {
  RadiositySystem system;
  Eigen::MatrixXd form_factors;
};

PhysicalSystem random_physical_system(std::size_t n, uint64_t seed) {
  Pcg32 rng(seed, 7);
  PhysicalSystem result;
  RadiositySystem& system = result.system;
  for (std::size_t i = 0; i < n; ++i) {
    system.areas.push_back(0.5 + 1.5 * rng.next_double());
    system.reflectance.emplace_back(0.2 + 0.6 * rng.next_double(), 0.2 + 0.6 * rng.next_double(),
                                    0.2 + 0.6 * rng.next_double());
    system.emission.emplace_back(0.0);
  }
  for (std::size_t k = 0; k < 3; ++k) {
    system.emission[(k * 17 + 3) % n] =
        Color(1 + 4 * rng.next_double(), 1 + 4 * rng.next_double(), 1 + 4 * rng.next_double());
  }
  const auto size = static_cast<Eigen::Index>(n);
  Eigen::MatrixXd weights = Eigen::MatrixXd::Zero(size, size);  // symmetric, zero diagonal
  for (Eigen::Index i = 0; i < size; ++i) {
    for (Eigen::Index j = i + 1; j < size; ++j) {
      const double w = rng.next_double() < 0.2 ? 0.0 : 0.5 + rng.next_double();
      weights(i, j) = weights(j, i) = w;
    }
  }
  // G_ij = s A_i A_j w_ij, s chosen so that the largest Σ_j G_ij / A_i is 1.
  double largest_row_sum = 0;
  for (Eigen::Index i = 0; i < size; ++i) {
    double row_sum = 0;
    for (Eigen::Index j = 0; j < size; ++j) row_sum += system.areas[j] * weights(i, j);
    largest_row_sum = std::max(largest_row_sum, row_sum);
  }
  result.form_factors.resize(size, size);
  for (Eigen::Index i = 0; i < size; ++i) {
    for (Eigen::Index j = 0; j < size; ++j) {
      const double g = system.areas[i] * system.areas[j] * weights(i, j) / largest_row_sum;
      result.form_factors(i, j) = g / system.areas[i];
    }
  }
  return result;
}

double largest_relative_difference(const std::vector<Color>& actual, const std::vector<Color>& expected) {
  double largest = 0;
  for (std::size_t i = 0; i < actual.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      largest = std::max(largest, std::fabs(actual[i][c] - expected[i][c]) / std::fabs(expected[i][c]));
    }
  }
  return largest;
}

double rms_difference(const std::vector<Color>& actual, const std::vector<Color>& expected) {
  double sum = 0;
  for (std::size_t i = 0; i < actual.size(); ++i) {
    for (int c = 0; c < 3; ++c) sum += (actual[i][c] - expected[i][c]) * (actual[i][c] - expected[i][c]);
  }
  return std::sqrt(sum / (3.0 * static_cast<double>(actual.size())));
}

// A row provider over a dense matrix that counts its calls.
FormFactorSource counting_provider(const Eigen::MatrixXd& matrix, std::size_t& calls) {
  return FormFactorSource(static_cast<std::size_t>(matrix.rows()), static_cast<std::size_t>(matrix.cols()),
                          [matrix, &calls](std::size_t i, std::vector<double>& row) {
                            ++calls;
                            for (std::size_t j = 0; j < row.size(); ++j) {
                              row[j] = matrix(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j));
                            }
                          });
}

// ---- The furnace: a closed sphere of uniform E and ρ has B = E / (1 − ρ) everywhere ---------

const Color kFurnaceReflectance(0.5, 0.7, 0.9);
const Color kFurnaceEmission(1.0, 2.0, 0.5);

Color furnace_radiosity() {
  return {kFurnaceEmission.r / (1 - kFurnaceReflectance.r), kFurnaceEmission.g / (1 - kFurnaceReflectance.g),
          kFurnaceEmission.b / (1 - kFurnaceReflectance.b)};
}

void expect_furnace(const std::vector<Color>& radiosity, double relative_tolerance) {
  const Color expected = furnace_radiosity();
  ASSERT_FALSE(radiosity.empty());
  for (std::size_t i = 0; i < radiosity.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(radiosity[i][c], expected[c], relative_tolerance * expected[c])
          << "patch " << i << " channel " << c;
    }
  }
}

TEST(RadiositySolverFurnace, GaussianEliminationGivesEOverOneMinusRho) {
  for (const SpherePatches& sphere : {equal_area_sphere(), unequal_area_sphere(11)}) {
    const RadiositySystem system = uniform_system(sphere.areas, kFurnaceReflectance, kFurnaceEmission);
    const RadiositySolution dense = solve_gaussian_elimination(system, FormFactorSource(sphere.form_factors));
    expect_furnace(dense.radiosity, 1e-9);
    EXPECT_LT(dense.residual, 1e-12);
    EXPECT_EQ(dense.iterations, 1u);
    // The same matrix from a row provider: every row read once, the same numbers.
    std::size_t calls = 0;
    const RadiositySolution rows =
        solve_gaussian_elimination(system, counting_provider(sphere.form_factors, calls));
    EXPECT_EQ(calls, sphere.areas.size());
    EXPECT_EQ(rows.rows_computed, sphere.areas.size());
    for (std::size_t i = 0; i < system.size(); ++i) EXPECT_EQ(rows.radiosity[i], dense.radiosity[i]);
  }
}

TEST(RadiositySolverFurnace, GaussSeidelWithinItsTolerance) {
  const double tolerance = 1e-10;
  for (const SpherePatches& sphere : {equal_area_sphere(), unequal_area_sphere(12)}) {
    const RadiositySystem system = uniform_system(sphere.areas, kFurnaceReflectance, kFurnaceEmission);
    const RadiositySolution solution =
        solve_gauss_seidel(system, FormFactorSource(sphere.form_factors), tolerance, 10000);
    EXPECT_TRUE(solution.converged);
    EXPECT_LE(solution.relative_change, tolerance);
    // The error left after a sweep is at most ρ/(1 − ρ) times its change: 9× for ρ = 0.9.
    expect_furnace(solution.radiosity, 10 * tolerance);
    EXPECT_LT(solution.residual, 10 * tolerance);
  }
}

TEST(RadiositySolverFurnace, ProgressiveWithinOnePercentAtUnshotFractionOnePerMille) {
  for (const SpherePatches& sphere : {equal_area_sphere(), unequal_area_sphere(13)}) {
    ProgressiveRefinement progressive(uniform_system(sphere.areas, kFurnaceReflectance, kFurnaceEmission),
                                      FormFactorSource(sphere.form_factors));
    const ProgressiveRunResult result = progressive.run(0.001);
    EXPECT_TRUE(result.converged);
    EXPECT_LE(result.unshot_fraction, 0.001);
    EXPECT_EQ(progressive.steps(), result.steps);
    EXPECT_EQ(progressive.rows_computed(), result.steps);
    expect_furnace(progressive.radiosity(), 0.01);
    // Without the ambient term the progressive solution only ever falls short of the answer.
    for (const Color& b : progressive.radiosity()) {
      for (int c = 0; c < 3; ++c) EXPECT_LE(b[c], furnace_radiosity()[c] * (1 + 1e-12));
    }
  }
}

// ---- Two patches solved by hand ----------------------------------------------------------------

TEST(RadiositySolverTwoPatch, MatchesTheClosedForm) {
  // A_1 F_12 = A_2 F_21 (000 eq. 6-5); no patch sees itself. 000 eq. 6-8 for n = 2:
  //   B_1 = E_1 + ρ_1 F_12 B_2,  B_2 = E_2 + ρ_2 F_21 B_1
  // → B_1 = (E_1 + ρ_1 F_12 E_2) / (1 − ρ_1 ρ_2 F_12 F_21), and symmetrically.
  const double a1 = 1.0, a2 = 2.0, f12 = 0.4, f21 = a1 * f12 / a2;
  const Color rho1(0.8, 0.5, 0.3), rho2(0.6, 0.9, 0.4);
  const Color e1(1.0, 0.5, 0.0), e2(0.0, 0.2, 0.25);
  const RadiositySystem system{{a1, a2}, {rho1, rho2}, {e1, e2}};
  Eigen::MatrixXd f(2, 2);
  f << 0, f12, f21, 0;
  std::vector<Color> expected(2);
  for (int c = 0; c < 3; ++c) {
    const double denominator = 1 - rho1[c] * rho2[c] * f12 * f21;
    expected[0][c] = (e1[c] + rho1[c] * f12 * e2[c]) / denominator;
    expected[1][c] = (e2[c] + rho2[c] * f21 * e1[c]) / denominator;
  }
  const auto expect_matches = [&](const std::vector<Color>& actual, double tolerance, const char* solver) {
    for (std::size_t i = 0; i < 2; ++i) {
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(actual[i][c], expected[i][c], tolerance) << solver << " " << i << c;
    }
  };
  expect_matches(solve_gaussian_elimination(system, FormFactorSource(f)).radiosity, 1e-14, "elimination");
  expect_matches(solve_gauss_seidel(system, FormFactorSource(f), 1e-13).radiosity, 1e-12, "Gauss-Seidel");
  ProgressiveRefinement progressive(system, FormFactorSource(f));
  EXPECT_EQ(progressive.next_shooter(), 0u);  // flux 1.5 × 1 against 0.45 × 2
  EXPECT_TRUE(progressive.run(1e-14).converged);
  expect_matches(progressive.radiosity(), 1e-12, "progressive");
}

// ---- Progressive refinement (000 §6.6) -----------------------------------------------------

TEST(RadiositySolverProgressive, RandomPhysicalSystemIsReciprocalWithRowSumsAtMostOne) {
  const PhysicalSystem physical = random_physical_system(60, 5);
  const auto n = physical.form_factors.rows();
  double largest_row_sum = 0, smallest_row_sum = 1;
  for (Eigen::Index i = 0; i < n; ++i) {
    const double row_sum = physical.form_factors.row(i).sum();
    largest_row_sum = std::max(largest_row_sum, row_sum);
    smallest_row_sum = std::min(smallest_row_sum, row_sum);
    for (Eigen::Index j = 0; j < n; ++j) {
      EXPECT_NEAR(physical.system.areas[i] * physical.form_factors(i, j),
                  physical.system.areas[j] * physical.form_factors(j, i), 1e-15);
    }
  }
  EXPECT_NEAR(largest_row_sum, 1.0, 1e-12);
  EXPECT_GT(smallest_row_sum, 0.5);  // nearly closed: what the ambient estimate assumes
}

TEST(RadiositySolverProgressive, AgreesWithGaussianEliminationWithinHalfAPercent) {
  const PhysicalSystem physical = random_physical_system(60, 5);
  const RadiositySolution direct =
      solve_gaussian_elimination(physical.system, FormFactorSource(physical.form_factors));
  std::size_t calls = 0;
  ProgressiveRefinement progressive(physical.system, counting_provider(physical.form_factors, calls));
  const ProgressiveRunResult result = progressive.run(0.001);
  EXPECT_TRUE(result.converged);
  EXPECT_EQ(calls, result.steps);  // one row per step, nothing else read
  EXPECT_LT(largest_relative_difference(progressive.radiosity(), direct.radiosity), 0.005);
  // Gauss-Seidel agrees with both.
  const RadiositySolution iterated =
      solve_gauss_seidel(physical.system, FormFactorSource(physical.form_factors), 1e-12);
  EXPECT_LT(largest_relative_difference(iterated.radiosity, direct.radiosity), 1e-10);
}

TEST(RadiositySolverProgressive, UnshotFluxNeverIncreases) {
  const PhysicalSystem physical = random_physical_system(60, 8);
  ProgressiveRefinement progressive(physical.system, FormFactorSource(physical.form_factors));
  std::vector<double> fractions = {progressive.unshot_fraction()};
  std::vector<std::size_t> steps;
  progressive.run(1e-6, 5000, [&](std::size_t step, double unshot_fraction) {
    steps.push_back(step);
    fractions.push_back(unshot_fraction);
  });
  EXPECT_DOUBLE_EQ(fractions.front(), 1.0);
  ASSERT_GT(steps.size(), 10u);
  for (std::size_t k = 0; k < steps.size(); ++k) EXPECT_EQ(steps[k], k + 1);
  for (std::size_t k = 1; k < fractions.size(); ++k) {
    EXPECT_LE(fractions[k], fractions[k - 1]) << "step " << k;
  }
  EXPECT_LE(fractions.back(), 1e-6);
}

TEST(RadiositySolverProgressive, ShootsTheLargestUnshotFluxLowestIndexOnTies) {
  // Equal areas and emissions: a tie everywhere, patch 0 first; after it has shot, its unshot
  // radiosity is only what it received back, so patch 1 is next.
  const SpherePatches sphere = equal_area_sphere();
  ProgressiveRefinement progressive(uniform_system(sphere.areas, Color(0.5), Color(1.0)),
                                    FormFactorSource(sphere.form_factors));
  EXPECT_EQ(progressive.next_shooter(), 0u);
  ASSERT_TRUE(progressive.step());
  EXPECT_EQ(progressive.next_shooter(), 1u);
  // The largest unshot flux ΔB_j·A_j, not the largest ΔB_j: a dim but large patch goes first.
  const RadiositySystem system{{1.0, 10.0}, {Color(0.5), Color(0.5)}, {Color(3.0), Color(1.0)}};
  Eigen::MatrixXd f(2, 2);
  f << 0, 1, 0.1, 0.9;
  ProgressiveRefinement flux_order(system, FormFactorSource(f));
  EXPECT_EQ(flux_order.next_shooter(), 1u);
  // Nothing emitted: nothing to shoot.
  ProgressiveRefinement dark(uniform_system(sphere.areas, Color(0.5), Color(0.0)),
                             FormFactorSource(sphere.form_factors));
  EXPECT_EQ(dark.next_shooter(), sphere.areas.size());
  EXPECT_FALSE(dark.step());
  EXPECT_EQ(dark.unshot_fraction(), 0.0);
  EXPECT_EQ(dark.run().steps, 0u);
}

TEST(RadiositySolverProgressive, StopsAtMaxStepsAndResumes) {
  const PhysicalSystem physical = random_physical_system(40, 3);
  ProgressiveRefinement progressive(physical.system, FormFactorSource(physical.form_factors));
  const ProgressiveRunResult first = progressive.run(0.001, 5);
  EXPECT_EQ(first.steps, 5u);
  EXPECT_FALSE(first.converged);
  EXPECT_GT(first.unshot_fraction, 0.001);
  const ProgressiveRunResult rest = progressive.run(0.001);
  EXPECT_TRUE(rest.converged);
  EXPECT_EQ(progressive.steps(), first.steps + rest.steps);
  // Stopping and resuming changes nothing: the same as one uninterrupted run.
  ProgressiveRefinement uninterrupted(physical.system, FormFactorSource(physical.form_factors));
  uninterrupted.run(0.001);
  EXPECT_EQ(uninterrupted.steps(), progressive.steps());
  for (std::size_t i = 0; i < physical.system.size(); ++i) {
    EXPECT_EQ(uninterrupted.radiosity()[i], progressive.radiosity()[i]);
  }
}

TEST(RadiositySolverProgressive, AmbientFollowsTheSeedFormulaAndVanishes) {
  // 000 §6.6.2 before any step: ΔB = E, so B_amb = (Σ E_i A_i / Σ A_i) / (1 − ρ_avg),
  // ρ_avg = Σ ρ_i A_i / Σ A_i (000 eq. 6-14).
  const PhysicalSystem physical = random_physical_system(30, 21);
  const RadiositySystem& system = physical.system;
  ProgressiveRefinement progressive(system, FormFactorSource(physical.form_factors));
  double total_area = 0;
  Color reflectance_area, emission_area;
  for (std::size_t i = 0; i < system.size(); ++i) {
    total_area += system.areas[i];
    reflectance_area += system.reflectance[i] * system.areas[i];
    emission_area += system.emission[i] * system.areas[i];
  }
  const Color ambient = progressive.ambient();
  for (int c = 0; c < 3; ++c) {
    const double average_reflectance = reflectance_area[c] / total_area;
    EXPECT_NEAR(ambient[c], emission_area[c] / total_area / (1 - average_reflectance), 1e-12);
  }
  const Color display = progressive.display_radiosity(4, true);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(display[c], progressive.radiosity()[4][c] + system.reflectance[4][c] * ambient[c], 1e-15);
  }
  EXPECT_EQ(progressive.display_radiosity(4, false), progressive.radiosity()[4]);
  progressive.run(1e-6);
  EXPECT_LT(progressive.ambient().max_component(), 1e-5 * ambient.max_component());
}

TEST(RadiositySolverProgressive, AmbientBringsEarlyStepsCloserToTheSolution) {
  const PhysicalSystem physical = random_physical_system(60, 5);
  const std::vector<Color> converged =
      solve_gaussian_elimination(physical.system, FormFactorSource(physical.form_factors)).radiosity;
  ProgressiveRefinement progressive(physical.system, FormFactorSource(physical.form_factors));
  for (const std::size_t snapshot : {1u, 2u, 20u}) {
    progressive.run(0.0, snapshot - progressive.steps());
    ASSERT_EQ(progressive.steps(), snapshot);
    const double without_ambient = rms_difference(progressive.display_radiosities(false), converged);
    const double with_ambient = rms_difference(progressive.display_radiosities(true), converged);
    EXPECT_LT(with_ambient, 0.75 * without_ambient) << "after " << snapshot << " steps";
  }
}

TEST(RadiositySolverProgressive, AmbientIsExactInTheUniformClosedSphere) {
  // There F_ji = A_i / ΣA, the seed's estimate, holds exactly and ρ_avg = ρ: with the ambient
  // term every step already displays the converged answer E / (1 − ρ).
  const SpherePatches sphere = unequal_area_sphere(17);
  ProgressiveRefinement progressive(uniform_system(sphere.areas, kFurnaceReflectance, kFurnaceEmission),
                                    FormFactorSource(sphere.form_factors));
  for (int step = 0; step < 5; ++step) {
    expect_furnace(progressive.display_radiosities(true), 1e-12);
    ASSERT_TRUE(progressive.step());
  }
}

// ---- Energy ----------------------------------------------------------------------------------

TEST(RadiositySolverEnergy, ClosedSphereAbsorbsWhatItEmits) {
  // One emitter, random reflectances, unequal patches. With the irradiance H_i = Σ_j F_ij B_j:
  //   Σ B_i A_i = Σ E_i A_i + Σ ρ_i H_i A_i   (000 eq. 6-1 summed: leaving = emitted + reflected)
  //   Σ (1 − ρ_i) H_i A_i = Σ E_i A_i         (closed: everything emitted is absorbed)
  const SpherePatches sphere = unequal_area_sphere(23);
  const std::size_t n = sphere.areas.size();
  Pcg32 rng(23, 2);
  RadiositySystem system{sphere.areas, {}, std::vector<Color>(n, Color(0.0))};
  for (std::size_t i = 0; i < n; ++i) {
    system.reflectance.emplace_back(0.9 * rng.next_double(), 0.9 * rng.next_double(),
                                    0.9 * rng.next_double());
  }
  system.emission[4] = Color(10.0, 5.0, 1.0);
  const RadiositySolution solution =
      solve_gaussian_elimination(system, FormFactorSource(sphere.form_factors));
  for (int c = 0; c < 3; ++c) {
    double leaving = 0, emitted = 0, reflected = 0, absorbed = 0;
    for (std::size_t i = 0; i < n; ++i) {
      double irradiance = 0;
      for (std::size_t j = 0; j < n; ++j) {
        irradiance += sphere.form_factors(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) *
                      solution.radiosity[j][c];
      }
      leaving += solution.radiosity[i][c] * sphere.areas[i];
      emitted += system.emission[i][c] * sphere.areas[i];
      reflected += system.reflectance[i][c] * irradiance * sphere.areas[i];
      absorbed += (1 - system.reflectance[i][c]) * irradiance * sphere.areas[i];
    }
    EXPECT_NEAR(leaving, emitted + reflected, 1e-10 * leaving) << "channel " << c;
    EXPECT_NEAR(absorbed, emitted, 1e-10 * emitted) << "channel " << c;
  }
}

TEST(RadiositySolverEnergy, ProgressiveBalancesEveryStepInTheClosedSphere) {
  // Uniform ρ, one emitter. Shooting moves all of ΔB_j A_j onto the sphere (rows sum to 1), ρ of
  // it comes back as radiosity and unshot radiosity, so after any step with unshot flux U:
  //   Σ B_i A_i = (Σ E_i A_i − ρ U) / (1 − ρ)
  // and at U = 0 the total leaving flux is the furnace's emitted / (1 − ρ).
  const SpherePatches sphere = unequal_area_sphere(29);
  const std::size_t n = sphere.areas.size();
  RadiositySystem system = uniform_system(sphere.areas, kFurnaceReflectance, Color(0.0));
  system.emission[7] = Color(3.0, 2.0, 1.0);
  ProgressiveRefinement progressive(system, FormFactorSource(sphere.form_factors));
  const auto expect_balance = [&] {
    for (int c = 0; c < 3; ++c) {
      double leaving = 0, unshot = 0, emitted = 0;
      for (std::size_t i = 0; i < n; ++i) {
        leaving += progressive.radiosity()[i][c] * sphere.areas[i];
        unshot += progressive.unshot_radiosity()[i][c] * sphere.areas[i];
        emitted += system.emission[i][c] * sphere.areas[i];
      }
      const double rho = kFurnaceReflectance[c];
      EXPECT_NEAR(leaving, (emitted - rho * unshot) / (1 - rho), 1e-10 * leaving)
          << "step " << progressive.steps() << " channel " << c;
    }
  };
  expect_balance();
  for (int step = 0; step < 50; ++step) {
    ASSERT_TRUE(progressive.step());
    expect_balance();
  }
}

// ---- Gaussian elimination and Gauss-Seidel: limits and input checks --------------------------

TEST(RadiositySolverGaussianElimination, RefusesBeyondTheMemoryLimitNamingTheSettings) {
  const std::size_t n = 2000;  // 2 × 2000² doubles: 64 MB
  std::size_t calls = 0;
  const FormFactorSource rows(n, n, [&calls](std::size_t, std::vector<double>&) { ++calls; });
  const RadiositySystem system = uniform_system(std::vector<double>(n, 1.0), Color(0.5), Color(1.0));
  try {
    solve_gaussian_elimination(system, rows, uint64_t{1} << 20);
    FAIL() << "expected SolverMemoryError";
  } catch (const SolverMemoryError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("radiosity.solver"), std::string::npos) << message;
    EXPECT_NE(message.find("\"progressive\""), std::string::npos) << message;
    EXPECT_NE(message.find("radiosity.patch_size"), std::string::npos) << message;
    EXPECT_EQ(error.required_bytes(), gaussian_elimination_memory_bytes(n));
    EXPECT_EQ(error.limit_bytes(), uint64_t{1} << 20);
  }
  EXPECT_EQ(calls, 0u);  // refused before computing a single row
  // A setting that asks too much is bad input (an InputError, exit 2), no longer invalid_argument.
  EXPECT_THROW(solve_gaussian_elimination(system, rows, uint64_t{1} << 20), InputError);
  EXPECT_GE(gaussian_elimination_memory_bytes(n), 2 * n * n * sizeof(double));
  EXPECT_GT(gaussian_elimination_memory_bytes(2 * n), 3 * gaussian_elimination_memory_bytes(n));
  EXPECT_GE(default_gaussian_elimination_memory_limit(), uint64_t{1} << 20);
  // Within the limit it solves.
  const SpherePatches sphere = equal_area_sphere();
  const RadiositySystem furnace = uniform_system(sphere.areas, kFurnaceReflectance, kFurnaceEmission);
  expect_furnace(
      solve_gaussian_elimination(furnace, FormFactorSource(sphere.form_factors), uint64_t{1} << 20).radiosity,
      1e-9);
}

TEST(RadiositySolverGaussianElimination, RejectsAClosedEnclosureOfPerfectReflectors) {
  const SpherePatches sphere = equal_area_sphere();
  const RadiositySystem system = uniform_system(sphere.areas, Color(1.0), Color(1.0));
  EXPECT_THROW(solve_gaussian_elimination(system, FormFactorSource(sphere.form_factors)), std::runtime_error);
}

TEST(RadiositySolverGaussSeidel, ReportsSweepsAndStopsAtMaxIterations) {
  const PhysicalSystem physical = random_physical_system(30, 2);
  std::size_t calls = 0;
  std::vector<double> changes;
  std::vector<Color> last;
  const RadiositySolution solution =
      solve_gauss_seidel(physical.system, counting_provider(physical.form_factors, calls), 1e-9, 1000,
                         [&](std::size_t sweep, double change, const std::vector<Color>& radiosity) {
                           EXPECT_EQ(sweep, changes.size() + 1);
                           changes.push_back(change);
                           last = radiosity;
                         });
  EXPECT_EQ(last, solution.radiosity);  // the last sweep's radiosities are the solution
  EXPECT_TRUE(solution.converged);
  EXPECT_EQ(solution.iterations, changes.size());
  EXPECT_LE(changes.back(), 1e-9);
  EXPECT_EQ(solution.relative_change, changes.back());
  EXPECT_LT(solution.residual, 1e-8);
  EXPECT_DOUBLE_EQ(
      solution.residual,
      radiosity_residual(physical.system, FormFactorSource(physical.form_factors), solution.radiosity));
  // Every sweep reads every row, and the final residual reads them once more.
  EXPECT_EQ(calls, (solution.iterations + 1) * physical.system.size());
  EXPECT_EQ(solution.rows_computed, calls);
  // One sweep is not enough at this tolerance.
  const RadiositySolution cut_short =
      solve_gauss_seidel(physical.system, FormFactorSource(physical.form_factors), 1e-9, 1);
  EXPECT_FALSE(cut_short.converged);
  EXPECT_EQ(cut_short.iterations, 1u);
  EXPECT_GT(cut_short.relative_change, 1e-9);
}

TEST(RadiositySolverInput, RejectsMalformedSystemsAndSources) {
  const Eigen::MatrixXd f = Eigen::MatrixXd::Constant(2, 2, 0.5);
  const RadiositySystem good{{1.0, 1.0}, {Color(0.5), Color(0.5)}, {Color(1.0), Color(0.0)}};
  EXPECT_NO_THROW(good.validate());
  RadiositySystem bad = good;
  bad.areas[1] = 0;
  EXPECT_THROW(solve_gaussian_elimination(bad, FormFactorSource(f)), std::invalid_argument);
  bad = good;
  bad.reflectance[0] = Color(0.5, 1.5, 0.5);
  EXPECT_THROW(solve_gauss_seidel(bad, FormFactorSource(f)), std::invalid_argument);
  bad = good;
  bad.emission[1] = Color(-1.0);
  EXPECT_THROW(ProgressiveRefinement(bad, FormFactorSource(f)), std::invalid_argument);
  bad = good;
  bad.emission.pop_back();
  EXPECT_THROW(bad.validate(), std::invalid_argument);
  // Wrong shape, a provider that resizes its row, a non-finite form factor, a bad tolerance.
  EXPECT_THROW(solve_gaussian_elimination(good, FormFactorSource(Eigen::MatrixXd::Zero(3, 3))),
               std::invalid_argument);
  const FormFactorSource resizing(2, 2, [](std::size_t, std::vector<double>& row) { row.push_back(0); });
  EXPECT_THROW(solve_gaussian_elimination(good, resizing), std::logic_error);
  Eigen::MatrixXd not_finite = f;
  not_finite(1, 0) = std::nan("");
  EXPECT_THROW(solve_gauss_seidel(good, FormFactorSource(not_finite)), std::invalid_argument);
  EXPECT_THROW(solve_gauss_seidel(good, FormFactorSource(f), 0.0), std::invalid_argument);
  EXPECT_THROW(solve_gauss_seidel(good, FormFactorSource(f), 1e-6, 0), std::invalid_argument);
  ProgressiveRefinement progressive(good, FormFactorSource(f));
  EXPECT_THROW(progressive.run(-1.0), std::invalid_argument);
  EXPECT_THROW(progressive.display_radiosity(2, false), std::out_of_range);
  EXPECT_THROW(FormFactorSource(2, 2, FormFactorRowProvider()), std::invalid_argument);
  // An empty system is solved trivially.
  EXPECT_TRUE(solve_gaussian_elimination(RadiositySystem{}, FormFactorSource(Eigen::MatrixXd(0, 0)))
                  .radiosity.empty());
}

// ---- Substructuring (000 §6.7.1) -------------------------------------------------------------

// The equal-area sphere's patches each split into `split` elements of equal area (sectors cut
// further): element q lies on patch q / split. Uniform ρ and E on every element.
ElementSystem sphere_elements(const SpherePatches& sphere, std::size_t split, const Color& reflectance,
                              const Color& emission) {
  ElementSystem elements;
  for (std::size_t i = 0; i < sphere.areas.size(); ++i) {
    for (std::size_t k = 0; k < split; ++k) {
      elements.patch.push_back(i);
      elements.areas.push_back(sphere.areas[i] / static_cast<double>(split));
      elements.reflectance.push_back(reflectance);
      elements.emission.push_back(emission);
    }
  }
  return elements;
}

TEST(RadiositySolverSubstructuring, ElementsSeeingIdenticalSurroundingsGetThePatchRadiosity) {
  // On the sphere every element sees the patches as its patch does: F_qj = A_j / A_sphere.
  const SpherePatches sphere = unequal_area_sphere(31);
  const std::size_t split = 4;
  const ElementSystem elements = sphere_elements(sphere, split, kFurnaceReflectance, kFurnaceEmission);
  const auto m = static_cast<Eigen::Index>(elements.size());
  const auto n = static_cast<Eigen::Index>(sphere.areas.size());
  Eigen::MatrixXd element_to_patch(m, n);
  for (Eigen::Index q = 0; q < m; ++q) element_to_patch.row(q) = sphere.form_factors.row(0);
  const RadiositySolution patches =
      solve_gaussian_elimination(uniform_system(sphere.areas, kFurnaceReflectance, kFurnaceEmission),
                                 FormFactorSource(sphere.form_factors));
  const std::vector<Color> element_radiosity =
      gather_element_radiosities(elements, FormFactorSource(element_to_patch), patches.radiosity);
  ASSERT_EQ(element_radiosity.size(), elements.size());
  for (std::size_t q = 0; q < elements.size(); ++q) {
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(element_radiosity[q][c], patches.radiosity[elements.patch[q]][c], 1e-12) << "element " << q;
    }
  }
  // And their area-weighted mean is the patch radiosity again.
  const std::vector<Color> averaged =
      patch_radiosities_from_elements(elements, element_radiosity, sphere.areas.size());
  for (std::size_t i = 0; i < sphere.areas.size(); ++i) {
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(averaged[i][c], patches.radiosity[i][c], 1e-12) << "patch " << i;
  }
}

TEST(RadiositySolverSubstructuring, AreaWeightedElementRowsReproduceThePatchFormFactor) {
  // 000 eq. 6-19 on the sphere: elements of any size see F_qj = A_j / A_sphere, and so must the
  // patches they form.
  const SpherePatches sphere = equal_area_sphere();
  const std::size_t n = sphere.areas.size();
  ElementSystem elements = sphere_elements(sphere, 3, Color(0.5), Color(0.0));
  for (std::size_t q = 0; q < elements.size(); ++q) {  // unequal elements, same patch areas
    elements.areas[q] = sphere.areas[elements.patch[q]] * (q % 3 == 0 ? 0.5 : 0.25);
  }
  const auto m = static_cast<Eigen::Index>(elements.size());
  Eigen::MatrixXd element_to_patch(m, static_cast<Eigen::Index>(n));
  for (Eigen::Index q = 0; q < m; ++q) element_to_patch.row(q) = sphere.form_factors.row(0);
  const Eigen::MatrixXd patch_form_factors =
      patch_form_factors_from_elements(elements, FormFactorSource(element_to_patch)).to_dense();
  EXPECT_LT((patch_form_factors - sphere.form_factors).cwiseAbs().maxCoeff(), 1e-15);

  // By hand: patch 0 of area 3 made of elements of areas 1 and 2 with rows (0.2, 0.8) and
  // (0.5, 0.5): F_0j = (1·(0.2, 0.8) + 2·(0.5, 0.5)) / 3 = (0.4, 0.6); patch 1 is one element.
  const ElementSystem two{
      {0, 0, 1}, {1.0, 2.0, 4.0}, std::vector<Color>(3, Color(0.5)), std::vector<Color>(3, Color(0.0))};
  Eigen::MatrixXd rows(3, 2);
  rows << 0.2, 0.8, 0.5, 0.5, 0.3, 0.7;
  std::size_t calls = 0;
  const FormFactorSource patch_source = patch_form_factors_from_elements(two, counting_provider(rows, calls));
  EXPECT_EQ(patch_source.rows(), 2u);
  EXPECT_EQ(patch_source.columns(), 2u);
  std::vector<double> row;
  patch_source.row(0, row);
  EXPECT_NEAR(row[0], 0.4, 1e-15);
  EXPECT_NEAR(row[1], 0.6, 1e-15);
  EXPECT_EQ(calls, 2u);  // only patch 0's elements were read
  patch_source.row(1, row);
  EXPECT_NEAR(row[0], 0.3, 1e-15);
  EXPECT_NEAR(row[1], 0.7, 1e-15);
}

TEST(RadiositySolverSubstructuring, PatchSolutionIsTheAreaWeightedMeanOfGatheredElements) {
  // 000 eqs. 6-17/6-18: with ρ and E uniform over each patch and patch form factors from eq. 6-19,
  // the patch solution B_i equals the area-weighted mean of its elements' B_q = E_q + ρ_q Σ F_qj B_j
  // (eq. 6-16), even though the elements differ from one another.
  const std::size_t n = 12, split = 3;
  Pcg32 rng(37, 4);
  RadiositySystem patches;
  ElementSystem elements;
  for (std::size_t i = 0; i < n; ++i) {
    const Color rho(0.2 + 0.6 * rng.next_double(), 0.2 + 0.6 * rng.next_double(),
                    0.2 + 0.6 * rng.next_double());
    const Color emission = i == 2 ? Color(4.0, 3.0, 2.0) : Color(0.0);
    double area = 0;
    for (std::size_t k = 0; k < split; ++k) {
      elements.patch.push_back(i);
      elements.areas.push_back(0.2 + rng.next_double());
      elements.reflectance.push_back(rho);
      elements.emission.push_back(emission);
      area += elements.areas.back();
    }
    patches.areas.push_back(area);
    patches.reflectance.push_back(rho);
    patches.emission.push_back(emission);
  }
  // Element rows: random, each summing to 0.95.
  Eigen::MatrixXd element_to_patch(static_cast<Eigen::Index>(n * split), static_cast<Eigen::Index>(n));
  for (Eigen::Index q = 0; q < element_to_patch.rows(); ++q) {
    for (Eigen::Index j = 0; j < element_to_patch.cols(); ++j) element_to_patch(q, j) = rng.next_double();
    element_to_patch.row(q) *= 0.95 / element_to_patch.row(q).sum();
  }
  const FormFactorSource element_source(element_to_patch);
  const FormFactorSource patch_source = patch_form_factors_from_elements(elements, element_source);
  const RadiositySolution solution = solve_gaussian_elimination(patches, patch_source);
  const std::vector<Color> element_radiosity =
      gather_element_radiosities(elements, element_source, solution.radiosity);
  const std::vector<Color> averaged = patch_radiosities_from_elements(elements, element_radiosity, n);
  EXPECT_LT(largest_relative_difference(averaged, solution.radiosity), 1e-12);
  // The elements of a patch really do differ.
  EXPECT_GT(std::fabs(element_radiosity[0].r - element_radiosity[1].r), 1e-3 * element_radiosity[0].r);
  // Mismatched inputs are rejected.
  EXPECT_THROW(gather_element_radiosities(elements, element_source, std::vector<Color>(n + 1)),
               std::invalid_argument);
  ElementSystem orphan = elements;
  for (std::size_t k = 1; k <= split; ++k) orphan.patch[orphan.size() - k] = n - 2;  // patch n − 1: none
  EXPECT_THROW(patch_form_factors_from_elements(orphan, element_source), std::invalid_argument);
  EXPECT_THROW(patch_radiosities_from_elements(orphan, element_radiosity, n), std::invalid_argument);
}

TEST(RadiositySolverSubstructuring, FloatElementRowsAreReadAsTheirDoubles) {
  // The method keeps its element rows as float (ElementToPatch); read in place through
  // element_to_patch_source they gather (000 eq. 6-16) and average (000 eq. 6-19) exactly as the
  // same values held as doubles.
  const SpherePatches sphere = unequal_area_sphere(43);
  const std::size_t split = 3;
  ElementSystem elements = sphere_elements(sphere, split, Color(0.5), Color(0.0));
  Pcg32 rng(43, 9);
  for (std::size_t q = 0; q < elements.size(); ++q) {
    elements.reflectance[q] = Color(0.2 + 0.6 * rng.next_double(), 0.5, 0.3);
    if (q == 4) elements.emission[q] = Color(2.0, 1.0, 0.5);
  }
  const auto m = static_cast<Eigen::Index>(elements.size());
  const auto n = static_cast<Eigen::Index>(sphere.areas.size());
  auto rows = std::make_shared<ElementToPatch>(m, n);
  for (Eigen::Index q = 0; q < m; ++q)
    for (Eigen::Index j = 0; j < n; ++j)
      (*rows)(q, j) = static_cast<float>(rng.next_double() / static_cast<double>(n));
  const FormFactorSource as_float = element_to_patch_source(rows);
  const FormFactorSource as_double(Eigen::MatrixXd(rows->cast<double>()));
  EXPECT_EQ(as_float.rows(), elements.size());
  EXPECT_EQ(as_float.columns(), sphere.areas.size());
  std::vector<Color> patch_radiosity;
  for (std::size_t i = 0; i < sphere.areas.size(); ++i)
    patch_radiosity.emplace_back(1.0 + static_cast<double>(i), 2.0, 0.5);
  const std::vector<Color> from_float = gather_element_radiosities(elements, as_float, patch_radiosity);
  const std::vector<Color> from_double = gather_element_radiosities(elements, as_double, patch_radiosity);
  for (std::size_t q = 0; q < elements.size(); ++q)
    EXPECT_EQ(from_float[q], from_double[q]) << "element " << q;
  const Eigen::MatrixXd patch_float = patch_form_factors_from_elements(elements, as_float).to_dense();
  const Eigen::MatrixXd patch_double = patch_form_factors_from_elements(elements, as_double).to_dense();
  EXPECT_TRUE(patch_float == patch_double);
  EXPECT_THROW(element_to_patch_source(nullptr), std::invalid_argument);
}

// ---- Progressive refinement with element receivers (000 §6.6 with §6.7.1) --------------------

// A substructured system: n patches of `split` elements each, ρ per patch, patch 2 (and its
// elements) emitting, and random element rows F_qj each summing to 0.95 with nothing to the
// element's own patch (as the method's hemicubes skip it).
struct SubstructuredSystem {
  RadiositySystem patches;
  ElementSystem elements;
  std::shared_ptr<ElementToPatch> rows;
};

SubstructuredSystem random_substructured_system(std::size_t n, std::size_t split, uint64_t seed) {
  Pcg32 rng(seed, 5);
  SubstructuredSystem result;
  for (std::size_t i = 0; i < n; ++i) {
    const Color rho(0.2 + 0.6 * rng.next_double(), 0.2 + 0.6 * rng.next_double(),
                    0.2 + 0.6 * rng.next_double());
    const Color emission = i == 2 ? Color(4.0, 3.0, 2.0) : Color(0.0);
    double area = 0;
    for (std::size_t k = 0; k < split; ++k) {
      result.elements.patch.push_back(i);
      result.elements.areas.push_back(0.2 + rng.next_double());
      result.elements.reflectance.push_back(rho);
      result.elements.emission.push_back(emission);
      area += result.elements.areas.back();
    }
    result.patches.areas.push_back(area);
    result.patches.reflectance.push_back(rho);
    result.patches.emission.push_back(emission);
  }
  const auto m = static_cast<Eigen::Index>(n * split);
  result.rows = std::make_shared<ElementToPatch>(m, static_cast<Eigen::Index>(n));
  ElementToPatch& rows = *result.rows;
  for (Eigen::Index q = 0; q < m; ++q) {
    for (Eigen::Index j = 0; j < rows.cols(); ++j)
      rows(q, j) = result.elements.patch[static_cast<std::size_t>(q)] == static_cast<std::size_t>(j)
                       ? 0.0f
                       : static_cast<float>(rng.next_double());
    rows.row(q) *= 0.95f / rows.row(q).sum();
  }
  return result;
}

// Element rows on the sphere: every element sees patch j as A_j / A_sphere.
std::shared_ptr<ElementToPatch> sphere_element_rows(const SpherePatches& sphere, std::size_t element_count) {
  auto rows = std::make_shared<ElementToPatch>(static_cast<Eigen::Index>(element_count),
                                               static_cast<Eigen::Index>(sphere.areas.size()));
  for (Eigen::Index q = 0; q < rows->rows(); ++q) rows->row(q) = sphere.form_factors.row(0).cast<float>();
  return rows;
}

TEST(RadiositySolverProgressiveElements, FurnaceWithinOnePercentAndTheAmbientTermExact) {
  const SpherePatches sphere = unequal_area_sphere(41);
  const ElementSystem elements = sphere_elements(sphere, 3, kFurnaceReflectance, kFurnaceEmission);
  const auto make = [&] {
    return ProgressiveRefinement(uniform_system(sphere.areas, kFurnaceReflectance, kFurnaceEmission),
                                 elements, sphere_element_rows(sphere, elements.size()));
  };
  ProgressiveRefinement progressive = make();
  EXPECT_EQ(progressive.size(), sphere.areas.size());
  EXPECT_EQ(progressive.radiosity().size(), elements.size());
  EXPECT_EQ(progressive.unshot_radiosity().size(), sphere.areas.size());
  // As with patches (AmbientIsExactInTheUniformClosedSphere), every step already displays the
  // converged answer (up to the float rows).
  for (int step = 0; step < 5; ++step) {
    expect_furnace(progressive.display_radiosities(true), 1e-6);
    ASSERT_TRUE(progressive.step());
  }
  ProgressiveRefinement converging = make();
  const ProgressiveRunResult result = converging.run(0.001);
  EXPECT_TRUE(result.converged);
  EXPECT_EQ(converging.rows_computed(), 0u);  // the element rows are given: no row is read from a source
  expect_furnace(converging.radiosity(), 0.01);
  for (const Color& b : converging.radiosity()) {
    for (int c = 0; c < 3; ++c) EXPECT_LE(b[c], furnace_radiosity()[c] * (1 + 1e-6));
  }
}

TEST(RadiositySolverProgressiveElements, OneElementPerPatchReadingItsOwnRowsMatchesThePatchShooter) {
  // Reciprocal F (A_i F_ij = A_j F_ji): patch receivers reading the shooter's row F_ji and element
  // receivers (one per patch) reading their own rows F_ij solve the same system.
  const PhysicalSystem physical = random_physical_system(40, 6);
  ElementSystem elements{{}, physical.system.areas, physical.system.reflectance, physical.system.emission};
  for (std::size_t i = 0; i < physical.system.size(); ++i) elements.patch.push_back(i);
  ProgressiveRefinement as_patches(physical.system, FormFactorSource(physical.form_factors));
  ProgressiveRefinement as_elements(physical.system, elements,
                                    std::make_shared<ElementToPatch>(physical.form_factors.cast<float>()));
  EXPECT_TRUE(as_patches.run(1e-10).converged);
  EXPECT_TRUE(as_elements.run(1e-10).converged);
  EXPECT_LT(largest_relative_difference(as_elements.radiosity(), as_patches.radiosity()), 1e-5);
  const RadiositySolution direct =
      solve_gaussian_elimination(physical.system, FormFactorSource(physical.form_factors));
  EXPECT_LT(largest_relative_difference(as_elements.radiosity(), direct.radiosity), 1e-5);
}

TEST(RadiositySolverProgressiveElements, ElementGainsFeedTheirPatchsUnshotRadiosityByArea) {
  // 000 eqs. 6-12, 6-13 with substructuring: the first shot from patch 2 gives element q
  // ΔRad_q = ρ_q ΔB_2 F_q2, and patch p's ΔB the area-weighted mean Σ_{q∈p} ΔRad_q A_q / A_p.
  const SubstructuredSystem sub = random_substructured_system(6, 3, 47);
  ProgressiveRefinement progressive(sub.patches, sub.elements, sub.rows);
  EXPECT_EQ(progressive.next_shooter(), 2u);
  ASSERT_TRUE(progressive.step());
  const Color shot = sub.patches.emission[2];
  std::vector<Color> patch_gain(sub.patches.size());
  for (std::size_t q = 0; q < sub.elements.size(); ++q) {
    const Color gain = sub.elements.reflectance[q] * shot *
                       static_cast<double>((*sub.rows)(static_cast<Eigen::Index>(q), 2));
    const Color expected = sub.elements.emission[q] + gain;
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(progressive.radiosity()[q][c], expected[c], 1e-15) << "element " << q;
    patch_gain[sub.elements.patch[q]] +=
        gain * (sub.elements.areas[q] / sub.patches.areas[sub.elements.patch[q]]);
  }
  for (std::size_t p = 0; p < sub.patches.size(); ++p) {
    // The shooter's own elements see nothing of it: its unshot radiosity is cleared and stays 0.
    const Color expected = p == 2 ? Color() : patch_gain[p];
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(progressive.unshot_radiosity()[p][c], expected[c], 1e-15) << "patch " << p;
  }
}

TEST(RadiositySolverProgressiveElements, AmbientWeighsElementReflectancesByArea) {
  // 000 §6.6.2 before any step: ΔB = E, so B_amb = (Σ_j E_j A_j / Σ A) / (1 − ρ_avg) with
  // ρ_avg = Σ_q ρ_q A_q / Σ A over the elements (000 eq. 6-14), elements of a patch differing.
  SubstructuredSystem sub = random_substructured_system(8, 3, 53);
  for (std::size_t q = 0; q < sub.elements.size(); ++q)
    sub.elements.reflectance[q] = Color(0.1 * static_cast<double>(q % 7), 0.4, 0.8);
  ProgressiveRefinement progressive(sub.patches, sub.elements, sub.rows);
  double total_area = 0;
  Color emission_area, reflectance_area;
  for (std::size_t j = 0; j < sub.patches.size(); ++j) {
    total_area += sub.patches.areas[j];
    emission_area += sub.patches.emission[j] * sub.patches.areas[j];
  }
  for (std::size_t q = 0; q < sub.elements.size(); ++q)
    reflectance_area += sub.elements.reflectance[q] * sub.elements.areas[q];
  const Color ambient = progressive.ambient();
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(ambient[c], emission_area[c] / total_area / (1 - reflectance_area[c] / total_area), 1e-12);
  for (const std::size_t q : {0u, 5u, 13u}) {
    EXPECT_EQ(progressive.display_radiosity(q, true),
              progressive.radiosity()[q] + sub.elements.reflectance[q] * ambient);
    EXPECT_EQ(progressive.display_radiosity(q, false), progressive.radiosity()[q]);
  }
  EXPECT_THROW(progressive.display_radiosity(sub.elements.size(), false), std::out_of_range);
  // A channel where everything reflects everything has no finite series: no ambient there.
  for (Color& rho : sub.elements.reflectance) rho.g = 1;
  const Color perfect_green = ProgressiveRefinement(sub.patches, sub.elements, sub.rows).ambient();
  EXPECT_EQ(perfect_green.g, 0.0);
  EXPECT_GT(perfect_green.r, 0.0);
}

TEST(RadiositySolverProgressiveElements, RestoredStateContinuesBitForBit) {
  // A checkpoint's state (B per element, ΔB per patch, the steps) continues to exactly
  // the uninterrupted run.
  const SubstructuredSystem sub = random_substructured_system(10, 4, 59);
  ProgressiveRefinement uninterrupted(sub.patches, sub.elements, sub.rows);
  uninterrupted.run(1e-4);
  ProgressiveRefinement first(sub.patches, sub.elements, sub.rows);
  first.run(1e-4, 7);
  ASSERT_EQ(first.steps(), 7u);
  ProgressiveRefinement resumed(sub.patches, sub.elements, sub.rows);
  resumed.restore(first.radiosity(), first.unshot_radiosity(), first.steps());
  EXPECT_EQ(resumed.steps(), 7u);
  EXPECT_EQ(resumed.next_shooter(), first.next_shooter());
  EXPECT_EQ(resumed.unshot_fraction(), first.unshot_fraction());
  std::vector<std::size_t> steps;
  resumed.run(1e-4, std::numeric_limits<std::size_t>::max(),
              [&](std::size_t step, double) { steps.push_back(step); });
  ASSERT_FALSE(steps.empty());
  EXPECT_EQ(steps.front(), 8u);  // counted on from the restored steps
  EXPECT_EQ(resumed.steps(), uninterrupted.steps());
  for (std::size_t q = 0; q < sub.elements.size(); ++q)
    EXPECT_EQ(resumed.radiosity()[q], uninterrupted.radiosity()[q]);
  for (std::size_t p = 0; p < sub.patches.size(); ++p)
    EXPECT_EQ(resumed.unshot_radiosity()[p], uninterrupted.unshot_radiosity()[p]);
  // A state of another size is refused.
  EXPECT_THROW(resumed.restore(std::vector<Color>(3), first.unshot_radiosity(), 0), std::invalid_argument);
  EXPECT_THROW(resumed.restore(first.radiosity(), std::vector<Color>(3), 0), std::invalid_argument);
}

TEST(RadiositySolverProgressiveElements, CancelIsAskedBeforeEveryStepWithTheStepsSoFar) {
  const SubstructuredSystem sub = random_substructured_system(10, 2, 61);
  ProgressiveRefinement progressive(sub.patches, sub.elements, sub.rows);
  std::vector<std::size_t> asked;
  const auto cancel_at_five = [&](std::size_t steps) {
    asked.push_back(steps);
    return steps == 5;
  };
  const ProgressiveRunResult stopped = progressive.run(1e-9, 1000, {}, cancel_at_five);
  EXPECT_EQ(stopped.steps, 5u);
  EXPECT_FALSE(stopped.converged);
  EXPECT_EQ(asked, (std::vector<std::size_t>{0, 1, 2, 3, 4, 5}));
  // Not asked when no step would follow: out of steps, or converged.
  const auto never = [&](std::size_t steps) {
    asked.push_back(steps);
    return false;
  };
  asked.clear();
  EXPECT_EQ(progressive.run(1e-9, 0, {}, never).steps, 0u);
  EXPECT_TRUE(asked.empty());
  const ProgressiveRunResult converged = progressive.run(0.01, 1000, {}, never);
  EXPECT_TRUE(converged.converged);
  EXPECT_EQ(asked.size(), converged.steps);  // once before each step, not after the last
  EXPECT_EQ(progressive.run(0.01, 1000, {}, never).steps, 0u);
  EXPECT_EQ(asked.size(), converged.steps);
}

TEST(RadiositySolverProgressiveElements, RejectsRowsOfTheWrongShapeAndBadElements) {
  const SubstructuredSystem sub = random_substructured_system(4, 2, 67);
  EXPECT_THROW(ProgressiveRefinement(sub.patches, sub.elements, nullptr), std::invalid_argument);
  EXPECT_THROW(ProgressiveRefinement(sub.patches, sub.elements,
                                     std::make_shared<ElementToPatch>(ElementToPatch::Zero(8, 3))),
               std::invalid_argument);
  EXPECT_THROW(ProgressiveRefinement(sub.patches, sub.elements,
                                     std::make_shared<ElementToPatch>(ElementToPatch::Zero(7, 4))),
               std::invalid_argument);
  ElementSystem stray = sub.elements;
  stray.patch[3] = 4;  // no patch 4
  EXPECT_THROW(ProgressiveRefinement(sub.patches, stray, sub.rows), std::invalid_argument);
  ElementSystem flat = sub.elements;
  flat.areas[1] = 0;
  EXPECT_THROW(ProgressiveRefinement(sub.patches, flat, sub.rows), std::invalid_argument);
  EXPECT_NO_THROW(ProgressiveRefinement(sub.patches, sub.elements, sub.rows));
}

}  // namespace
}  // namespace candela
