// Piecewise-constant distributions (pbrt-v3 §13.3.1 Distribution1D, §13.6.7 Distribution2D):
// sampling a function tabulated on n equal cells of [0, 1) (or of [0, 1)²) continuously with its
// density, and discretely (an index with its probability: the path tracer picks emitters by
// power with it; environment maps pick texels). Densities are exact for the tabulated function
// (negative and non-finite values count as 0). SPEC §12.
#pragma once

#include <cstddef>
#include <vector>

#include "math/vector.h"

namespace candela {

class Distribution1D {
 public:
  Distribution1D() = default;
  // Weights of the n cells; n may be 0 (nothing to sample).
  explicit Distribution1D(std::vector<double> weights);

  std::size_t size() const { return weights_.size(); }
  // Sum of the weights / n: the integral of the step function over [0, 1).
  double integral() const { return integral_; }
  double sum() const { return sum_; }
  // False when every weight is 0 (then sample_* return false and pdfs are 0).
  bool can_sample() const { return sum_ > 0; }
  double weight(std::size_t index) const { return weights_[index]; }

  // Discrete: the index i with probability weight(i) / sum(); remapped (optional) gets u's
  // position within the chosen cell's cdf interval, uniform in [0, 1) again.
  bool sample_discrete(double u, std::size_t& index, double& probability, double* remapped = nullptr) const;
  double discrete_probability(std::size_t index) const;

  // Continuous: x in [0, 1) with density weight(cell of x) / integral(); index is that cell.
  // The density returned equals pdf(x) bit for bit (x is kept inside the chosen cell).
  bool sample_continuous(double u, double& x, double& pdf, std::size_t* index = nullptr) const;
  double pdf(double x) const;
  // The cell x lies in (clamped to [0, n − 1]).
  std::size_t cell_of(double x) const;

 private:
  std::vector<double> weights_;
  std::vector<double> cdf_;  // n + 1 entries, cdf_[0] = 0, cdf_[n] = 1
  double sum_ = 0;
  double integral_ = 0;
};

// A step function on a grid of columns × rows over [0, 1)² (x along columns, y along rows):
// y is drawn from the marginal over rows, then x from that row's conditional.
class Distribution2D {
 public:
  Distribution2D() = default;
  // weights[row * columns + column].
  Distribution2D(const std::vector<double>& weights, std::size_t columns, std::size_t rows);

  bool can_sample() const { return marginal_.can_sample(); }
  std::size_t columns() const { return columns_; }
  std::size_t rows() const { return rows_; }
  double integral() const { return marginal_.integral(); }

  // A point of [0, 1)² with density f(cell) / integral; equals pdf(point) bit for bit.
  bool sample_continuous(const Vec2& u, Vec2& point, double& pdf) const;
  double pdf(const Vec2& point) const;

 private:
  std::size_t columns_ = 0, rows_ = 0;
  std::vector<Distribution1D> conditional_;  // one per row
  Distribution1D marginal_;                  // over rows, weights = row integrals
};

}  // namespace candela
