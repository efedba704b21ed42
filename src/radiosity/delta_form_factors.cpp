#include "radiosity/delta_form_factors.h"

#include <stdexcept>
#include <string>

#include "math/constants.h"

namespace candela {

namespace {

void check_resolution(int resolution) {
  if (resolution < 2 || resolution % 2 != 0)
    throw std::invalid_argument(
        "delta form factors: the hemicube resolution must be even and at least 2, not " +
        std::to_string(resolution));
}

// 000 §6.4.1: delta form factor, top face: ΔF = ΔA / (π (x² + y² + 1)²), x and y the cell centre.
// The centre coordinates come as odd integers over R (exact), so that the table and the direct
// evaluation compute bit-identical values whatever the sign or order of the coordinates.
double top_delta(int resolution, int odd_x, int odd_y) {
  const double x = static_cast<double>(odd_x) / resolution, y = static_cast<double>(odd_y) / resolution;
  const double cell_side = 2.0 / resolution;
  const double q = x * x + y * y + 1;
  return cell_side * cell_side / (kPi * q * q);
}

// 000 §6.4.1: delta form factor, side face: ΔF = z·ΔA / (π (y² + z² + 1)²), y along the face and
// z > 0 the height of the cell centre above the surface.
double side_delta(int resolution, int odd_y, int odd_z) {
  const double y = static_cast<double>(odd_y) / resolution, z = static_cast<double>(odd_z) / resolution;
  const double cell_side = 2.0 / resolution;
  const double q = y * y + z * z + 1;
  return z * (cell_side * cell_side) / (kPi * q * q);
}

}  // namespace

DeltaFormFactors::DeltaFormFactors(int resolution) : resolution_(resolution), half_(resolution / 2) {
  check_resolution(resolution);
  top_octant_.resize(octant_index(half_ - 1, half_ - 1) + 1);
  for (int a = 0; a < half_; ++a)
    for (int b = 0; b <= a; ++b)
      top_octant_[octant_index(a, b)] = top_delta(resolution, 2 * a + 1, 2 * b + 1);
  side_quarter_.resize(static_cast<std::size_t>(half_) * half_);
  for (int row = 0; row < half_; ++row) {
    const int odd_z = resolution - 2 * row - 1;  // the cell centre's height times R: R − 1 … 1
    for (int a = 0; a < half_; ++a)
      side_quarter_[static_cast<std::size_t>(row) * half_ + a] = side_delta(resolution, 2 * a + 1, odd_z);
  }
}

double DeltaFormFactors::at(HemicubeFace face, int column, int row) const {
  if (column < 0 || column >= resolution_ || row < 0 || row >= resolution_)
    throw std::out_of_range("delta form factors: cell (" + std::to_string(column) + ", " +
                            std::to_string(row) + ") is outside a face of resolution " +
                            std::to_string(resolution_));
  if (face == HemicubeFace::top) return top(column, row);
  return row < half_ ? side(column, row) : 0.0;
}

void DeltaFormFactors::expand_row(HemicubeFace face, int row, double* out) const {
  if (row < 0 || row >= resolution_)
    throw std::out_of_range("delta form factors: row " + std::to_string(row) +
                            " is outside a face of resolution " + std::to_string(resolution_));
  if (face == HemicubeFace::top) {
    // The row's folded index b is fixed: columns with a ≥ b read the octant's row a, the
    // others its column.
    const int b = fold(row);
    for (int column = 0; column < resolution_; ++column) {
      const int a = fold(column);
      out[column] = a >= b ? top_octant_[octant_index(a, b)] : top_octant_[octant_index(b, a)];
    }
  } else if (row < half_) {
    const double* stored = side_quarter_.data() + static_cast<std::size_t>(row) * half_;
    // Columns h … R−1 are the stored half; columns h−1 … 0 mirror it.
    for (int a = 0; a < half_; ++a) {
      out[half_ + a] = stored[a];
      out[half_ - 1 - a] = stored[a];
    }
  } else {
    for (int column = 0; column < resolution_; ++column) out[column] = 0.0;
  }
}

double DeltaFormFactors::evaluate(int resolution, HemicubeFace face, int column, int row) {
  check_resolution(resolution);
  if (column < 0 || column >= resolution || row < 0 || row >= resolution)
    throw std::out_of_range("delta form factors: cell (" + std::to_string(column) + ", " +
                            std::to_string(row) + ") is outside a face of resolution " +
                            std::to_string(resolution));
  const int odd_u = 2 * column + 1 - resolution;  // ndc u times R
  const int odd_v = resolution - 2 * row - 1;     // ndc v times R
  if (face == HemicubeFace::top) return top_delta(resolution, odd_u, odd_v);
  return odd_v > 0 ? side_delta(resolution, odd_u, odd_v) : 0.0;
}

double DeltaFormFactors::total() const {
  // Each face summed on its own (the four side faces hold the same values), then added.
  double top_sum = 0, side_sum = 0;
  for (int row = 0; row < resolution_; ++row)
    for (int column = 0; column < resolution_; ++column) top_sum += top(column, row);
  for (int row = 0; row < half_; ++row)
    for (int column = 0; column < resolution_; ++column) side_sum += side(column, row);
  return top_sum + 4 * side_sum;
}

}  // namespace candela
