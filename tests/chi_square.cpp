#include "chi_square.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>

namespace candela::test {

namespace {

constexpr double kPi = 3.14159265358979323846;

// ∫∫ f over [x0, x1] × [y0, y1] by composite 3-point Gauss–Legendre on n × n sub-cells. The
// nodes are interior, so a density that jumps on a cell's edge (a lobe cut off at the horizon,
// the rim of a cone) is integrated as well as a smooth one.
template <typename F>
double gauss_2d(F f, double x0, double x1, double y0, double y1, int n) {
  static constexpr double kNodes[3] = {-0.7745966692414834, 0.0, 0.7745966692414834};
  static constexpr double kWeights[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
  const double hx = (x1 - x0) / n, hy = (y1 - y0) / n;
  double sum = 0;
  for (int i = 0; i < n; ++i)
    for (int a = 0; a < 3; ++a) {
      const double x = x0 + (i + 0.5 * (1 + kNodes[a])) * hx;
      for (int j = 0; j < n; ++j)
        for (int b = 0; b < 3; ++b) {
          const double y = y0 + (j + 0.5 * (1 + kNodes[b])) * hy;
          sum += kWeights[a] * kWeights[b] * f(x, y);
        }
    }
  return sum * hx * hy / 4;
}

Vec3 spherical_direction(double theta, double phi) {
  const double sin_theta = std::sin(theta);
  return {sin_theta * std::cos(phi), sin_theta * std::sin(phi), std::cos(theta)};
}

std::vector<double> sphere_expected(const DirectionPdf& pdf, const SphereGrid& grid) {
  std::vector<double> cells(static_cast<std::size_t>(grid.theta_bins) * grid.phi_bins);
  const double dtheta = grid.theta_max / grid.theta_bins, dphi = 2 * kPi / grid.phi_bins;
  for (int i = 0; i < grid.theta_bins; ++i)
    for (int j = 0; j < grid.phi_bins; ++j)
      cells[static_cast<std::size_t>(i) * grid.phi_bins + j] = gauss_2d(
          [&](double theta, double phi) { return pdf(spherical_direction(theta, phi)) * std::sin(theta); },
          i * dtheta, (i + 1) * dtheta, j * dphi, (j + 1) * dphi, grid.subdivisions);
  return cells;
}

std::vector<double> rectangle_expected(const PointPdf& pdf, const RectangleGrid& grid) {
  std::vector<double> cells(static_cast<std::size_t>(grid.x_bins) * grid.y_bins);
  const double dx = (grid.x1 - grid.x0) / grid.x_bins, dy = (grid.y1 - grid.y0) / grid.y_bins;
  for (int i = 0; i < grid.x_bins; ++i)
    for (int j = 0; j < grid.y_bins; ++j)
      cells[static_cast<std::size_t>(i) * grid.y_bins + j] = gauss_2d(
          [&](double x, double y) {
            return pdf({x, y});
          },
          grid.x0 + i * dx, grid.x0 + (i + 1) * dx, grid.y0 + j * dy, grid.y0 + (j + 1) * dy,
          grid.subdivisions);
  return cells;
}

ChiSquareResult failed(const std::string& message) {
  ChiSquareResult result;
  result.p_value = 0;
  result.message = message;
  return result;
}

}  // namespace

double regularized_gamma_q(double a, double x) {
  if (!(x > 0)) return 1;
  constexpr double kEpsilon = 1e-15, kTiny = 1e-300;
  const double log_prefactor = -x + a * std::log(x) - std::lgamma(a);
  if (x < a + 1) {  // series for P(a, x)
    double term = 1 / a, sum = term, ap = a;
    for (int n = 0; n < 10000; ++n) {
      ap += 1;
      term *= x / ap;
      sum += term;
      if (std::fabs(term) < std::fabs(sum) * kEpsilon) break;
    }
    return std::clamp(1 - sum * std::exp(log_prefactor), 0.0, 1.0);
  }
  // Continued fraction for Q(a, x), modified Lentz.
  double b = x + 1 - a, c = 1 / kTiny, d = 1 / b, h = d;
  for (int i = 1; i < 10000; ++i) {
    const double an = -i * (i - a);
    b += 2;
    d = an * d + b;
    if (std::fabs(d) < kTiny) d = kTiny;
    c = b + an / c;
    if (std::fabs(c) < kTiny) c = kTiny;
    d = 1 / d;
    const double delta = d * c;
    h *= delta;
    if (std::fabs(delta - 1) < kEpsilon) break;
  }
  return std::clamp(std::exp(log_prefactor) * h, 0.0, 1.0);
}

double chi_square_p_value(double statistic, int degrees_of_freedom) {
  if (degrees_of_freedom <= 0) return 1;
  return regularized_gamma_q(degrees_of_freedom / 2.0, statistic / 2);
}

double sidak_significance(double alpha, int test_count) {
  return 1 - std::pow(1 - alpha, 1.0 / std::max(1, test_count));
}

ChiSquareResult chi_square_test(const std::vector<double>& observed, const std::vector<double>& expected,
                                double min_expected) {
  ChiSquareResult result;
  const std::size_t n = observed.size();
  result.expected_total = std::accumulate(expected.begin(), expected.end(), 0.0);
  const double observed_total = std::accumulate(observed.begin(), observed.end(), 0.0);
  result.accepted = static_cast<int>(observed_total);
  std::ostringstream summary;
  summary << "samples " << observed_total << ", expected " << result.expected_total;
  for (std::size_t i = 0; i < n; ++i) {
    if (expected[i] <= 0 && observed[i] > 0) {
      summary << "; cell " << i << " holds " << observed[i] << " samples where the density integrates to "
              << expected[i];
      result.message = summary.str();
      result.p_value = 0;
      return result;
    }
  }
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return expected[a] < expected[b]; });

  struct Term {
    double contribution;
    std::size_t cell;
    double observed, expected;
  };
  std::vector<Term> terms;
  double pool_observed = 0, pool_expected = 0;
  int cells = 0;
  for (const std::size_t i : order) {
    double o = observed[i], e = expected[i];
    if (e < min_expected) {
      pool_observed += o;
      pool_expected += e;
      ++result.pooled_cells;
      if (pool_expected < min_expected) continue;
      o = pool_observed;
      e = pool_expected;
      pool_observed = pool_expected = 0;
    } else if (pool_expected > 0 || pool_observed > 0) {
      // What the pool gathered below the threshold joins the smallest large cell.
      o += pool_observed;
      e += pool_expected;
      pool_observed = pool_expected = 0;
    }
    const double difference = o - e;
    terms.push_back({difference * difference / e, i, o, e});
    ++cells;
  }
  if (pool_expected > 0) {  // every cell was small
    const double difference = pool_observed - pool_expected;
    terms.push_back({difference * difference / pool_expected, n, pool_observed, pool_expected});
    ++cells;
  }
  for (const Term& term : terms) result.statistic += term.contribution;
  result.degrees_of_freedom = cells - 1;
  result.p_value = chi_square_p_value(result.statistic, result.degrees_of_freedom);
  std::sort(terms.begin(), terms.end(),
            [](const Term& a, const Term& b) { return a.contribution > b.contribution; });
  summary << "; chi2 " << result.statistic << " with " << result.degrees_of_freedom << " dof ("
          << result.pooled_cells << " cells pooled), p " << result.p_value << "; worst cells:";
  for (std::size_t k = 0; k < std::min<std::size_t>(5, terms.size()); ++k)
    summary << " [" << terms[k].cell << ": observed " << terms[k].observed << ", expected "
            << terms[k].expected << "]";
  result.message = summary.str();
  return result;
}

ChiSquareResult sphere_chi_square(const DirectionSampler& sample, const DirectionPdf& pdf, int sample_count,
                                  uint64_t seed, const SphereGrid& grid) {
  Pcg32 rng(seed, 0x9e3779b97f4a7c15ULL);
  std::vector<double> observed(static_cast<std::size_t>(grid.theta_bins) * grid.phi_bins, 0.0);
  for (int k = 0; k < sample_count; ++k) {
    Vec3 w;
    if (!sample(rng, w)) continue;
    if (!is_finite(w) || std::fabs(length(w) - 1) > 1e-6) {
      std::ostringstream message;
      message << "sample " << k << " is not a unit vector: " << w;
      return failed(message.str());
    }
    const double theta = std::acos(std::clamp(w.z, -1.0, 1.0));
    double phi = std::atan2(w.y, w.x);
    if (phi < 0) phi += 2 * kPi;
    if (theta > grid.theta_max) {
      std::ostringstream message;
      message << "sample " << k << " " << w << " lies beyond theta_max " << grid.theta_max;
      return failed(message.str());
    }
    const int i = std::min(grid.theta_bins - 1, static_cast<int>(theta / grid.theta_max * grid.theta_bins));
    const int j = std::min(grid.phi_bins - 1, static_cast<int>(phi / (2 * kPi) * grid.phi_bins));
    observed[static_cast<std::size_t>(i) * grid.phi_bins + j] += 1;
  }
  std::vector<double> expected = sphere_expected(pdf, grid);
  for (double& e : expected) e *= sample_count;
  return chi_square_test(observed, expected);
}

double integrate_over_sphere(const DirectionPdf& pdf, const SphereGrid& grid) {
  const std::vector<double> cells = sphere_expected(pdf, grid);
  return std::accumulate(cells.begin(), cells.end(), 0.0);
}

ChiSquareResult rectangle_chi_square(const PointSampler& sample, const PointPdf& pdf, int sample_count,
                                     uint64_t seed, const RectangleGrid& grid) {
  Pcg32 rng(seed, 0x2545f4914f6cdd1dULL);
  std::vector<double> observed(static_cast<std::size_t>(grid.x_bins) * grid.y_bins, 0.0);
  for (int k = 0; k < sample_count; ++k) {
    Vec2 p;
    if (!sample(rng, p)) continue;
    if (!(p.x >= grid.x0 && p.x <= grid.x1 && p.y >= grid.y0 && p.y <= grid.y1)) {
      std::ostringstream message;
      message << "sample " << k << " (" << p.x << ", " << p.y << ") lies outside the rectangle";
      return failed(message.str());
    }
    const int i =
        std::min(grid.x_bins - 1, static_cast<int>((p.x - grid.x0) / (grid.x1 - grid.x0) * grid.x_bins));
    const int j =
        std::min(grid.y_bins - 1, static_cast<int>((p.y - grid.y0) / (grid.y1 - grid.y0) * grid.y_bins));
    observed[static_cast<std::size_t>(i) * grid.y_bins + j] += 1;
  }
  std::vector<double> expected = rectangle_expected(pdf, grid);
  for (double& e : expected) e *= sample_count;
  return chi_square_test(observed, expected);
}

double integrate_over_rectangle(const PointPdf& pdf, const RectangleGrid& grid) {
  const std::vector<double> cells = rectangle_expected(pdf, grid);
  return std::accumulate(cells.begin(), cells.end(), 0.0);
}

}  // namespace candela::test
