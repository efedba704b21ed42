#include "sampling/piecewise_constant.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace candela {

namespace {
constexpr double kOneMinusEpsilon = 0x1.fffffffffffffp-1;
}  // namespace

Distribution1D::Distribution1D(std::vector<double> weights) : weights_(std::move(weights)) {
  for (double& w : weights_)
    if (!(w > 0) || !std::isfinite(w)) w = 0;
  const std::size_t n = weights_.size();
  cdf_.assign(n + 1, 0.0);
  for (std::size_t i = 0; i < n; ++i) cdf_[i + 1] = cdf_[i] + weights_[i];
  sum_ = cdf_[n];
  if (!(sum_ > 0) || !std::isfinite(sum_)) {
    sum_ = 0;
    integral_ = 0;
    return;
  }
  integral_ = sum_ / static_cast<double>(n);
  for (std::size_t i = 1; i <= n; ++i) cdf_[i] /= sum_;
  cdf_[n] = 1;
}

std::size_t Distribution1D::cell_of(double x) const {
  const double n = static_cast<double>(weights_.size());
  const double cell = std::floor(x * n);
  if (!(cell > 0)) return 0;
  if (cell >= n - 1) return weights_.size() - 1;
  return static_cast<std::size_t>(cell);
}

namespace {
// The cell i whose cdf interval [cdf[i], cdf[i + 1]) holds u; it has a positive weight.
std::size_t find_cell(const std::vector<double>& cdf, double u) {
  const auto after = std::upper_bound(cdf.begin(), cdf.end(), u);
  const std::size_t j = static_cast<std::size_t>(after - cdf.begin());
  const std::size_t last = cdf.size() - 2;
  std::size_t i = j == 0 ? 0 : std::min(j - 1, last);
  // u rounding onto a boundary of zero-width cells: step back to one with a weight.
  while (i > 0 && !(cdf[i + 1] > cdf[i])) --i;
  while (i < last && !(cdf[i + 1] > cdf[i])) ++i;
  return i;
}
}  // namespace

bool Distribution1D::sample_discrete(double u, std::size_t& index, double& probability,
                                     double* remapped) const {
  if (!can_sample()) return false;
  u = std::clamp(u, 0.0, kOneMinusEpsilon);
  index = find_cell(cdf_, u);
  probability = discrete_probability(index);
  if (remapped) {
    const double width = cdf_[index + 1] - cdf_[index];
    *remapped = std::clamp((u - cdf_[index]) / width, 0.0, kOneMinusEpsilon);
  }
  return true;
}

double Distribution1D::discrete_probability(std::size_t index) const {
  if (!can_sample() || index >= weights_.size()) return 0;
  return weights_[index] / sum_;
}

bool Distribution1D::sample_continuous(double u, double& x, double& density, std::size_t* index) const {
  if (!can_sample()) return false;
  u = std::clamp(u, 0.0, kOneMinusEpsilon);
  const std::size_t i = find_cell(cdf_, u);
  const double width = cdf_[i + 1] - cdf_[i];
  const double du = std::clamp((u - cdf_[i]) / width, 0.0, kOneMinusEpsilon);
  const double n = static_cast<double>(weights_.size());
  x = (static_cast<double>(i) + du) / n;
  // Keep x inside cell i despite rounding, so that pdf(x) is the density of the cell drawn.
  while (cell_of(x) > i) x = std::nextafter(x, 0.0);
  while (cell_of(x) < i) x = std::nextafter(x, 1.0);
  x = std::min(x, kOneMinusEpsilon);
  density = pdf(x);
  if (index) *index = i;
  return density > 0;
}

double Distribution1D::pdf(double x) const {
  if (!can_sample() || !(x >= 0 && x <= 1)) return 0;
  return weights_[cell_of(x)] / integral_;
}

Distribution2D::Distribution2D(const std::vector<double>& weights, std::size_t columns, std::size_t rows)
    : columns_(columns), rows_(rows) {
  if (weights.size() != columns * rows)
    throw std::invalid_argument("Distribution2D: weights do not fill the grid");
  conditional_.reserve(rows);
  std::vector<double> row_integrals(rows);
  for (std::size_t row = 0; row < rows; ++row) {
    conditional_.emplace_back(
        std::vector<double>(weights.begin() + static_cast<std::ptrdiff_t>(row * columns),
                            weights.begin() + static_cast<std::ptrdiff_t>((row + 1) * columns)));
    row_integrals[row] = conditional_.back().integral();
  }
  marginal_ = Distribution1D(std::move(row_integrals));
}

bool Distribution2D::sample_continuous(const Vec2& u, Vec2& point, double& density) const {
  if (!can_sample()) return false;
  double y_density = 0;
  std::size_t row = 0;
  if (!marginal_.sample_continuous(u.y, point.y, y_density, &row)) return false;
  double x_density = 0;
  if (!conditional_[row].sample_continuous(u.x, point.x, x_density)) return false;
  density = pdf(point);
  return density > 0;
}

double Distribution2D::pdf(const Vec2& point) const {
  if (!can_sample() || !(point.x >= 0 && point.x <= 1 && point.y >= 0 && point.y <= 1)) return 0;
  const std::size_t row = marginal_.cell_of(point.y);
  const Distribution1D& conditional = conditional_[row];
  // p(x, y) = p(y) · p(x | y) = (row integral / total) · (f / row integral) = f / total.
  return conditional.can_sample() ? conditional.weight(conditional.cell_of(point.x)) / marginal_.integral()
                                  : 0;
}

}  // namespace candela
