// Delta form factors of the hemicube (000 §6.4.1; Cohen and Greenberg 1985): the form factor
// from the differential patch at the hemicube's centre to one cell of one face, precomputed once
// per resolution and looked up by (face, image column, image row) when an item buffer is summed.
//
// Geometry: the cube of edge 2 around the patch centre, in the face frames of
// raster/hemicube_views.h. A face of resolution R has R × R cells of side 2/R, so
// ΔA = (2/R)²; cell (column, row) has its centre at ndc
//   u = (2·column + 1 − R)/R   (image right),   v = (R − 2·row − 1)/R   (image up).
// - Top face (distance 1 along n, (x, y) = (u, v)):  ΔF = ΔA / (π (x² + y² + 1)²).
// - Side face (distance 1 along its forward direction, which lies in the surface; the seed's
//   "y" along the face is u and its height above the surface z is v):
//       ΔF = z·ΔA / (π (y² + z² + 1)²)   for z > 0,
//   and 0 for the lower half of the image (rows ≥ R/2, z < 0: below the surface, never drawn).
// The sum over all cells of the five faces tends to 1 as R grows (the midpoint rule of the
// projected solid angle of the hemisphere; about 1e-5 short at R = 100).
//
// Storage (000 §6.4.1: "only 1/8 of the top face's and 1/4 of a side face's delta form factors
// need to be stored"): with h = R/2 and a cell's folded indices a = column − h for column ≥ h,
// h − 1 − column below (so that |u| = (2a + 1)/R), and b likewise from the row (|v| = (2b + 1)/R),
// - top_octant_ holds the octant 0 ≤ b ≤ a < h of the top face at index a(a+1)/2 + b: the top
//   face's ΔF depends on x² + y² only, so it is symmetric under x → −x, y → −y and x ↔ y;
//   h(h+1)/2 values;
// - side_quarter_ holds the upper half (rows 0 … h−1) of the right half of the columns of a side
//   face at index row·h + a: a side face's ΔF is symmetric under y → −y only; the four side
//   faces are identical (each face's image up is n in hemicube_views.h), so one table serves
//   all four; h² values.
// In all h(h+1)/2 + h² = 3R²/8 + R/4 values for the 3R² cells of the hemicube (R² top, 4 × R²/2
// above the surface on the sides): one eighth, plus R/4.
//
// The lookups are the same for every orientation of the face frames in hemicube_views.h: image
// rows and columns index the item buffer directly (row 0 at the top of the image, which is the
// side farthest from the surface on a side face).
#pragma once

#include <cstddef>
#include <vector>

#include "raster/hemicube_views.h"

namespace candela {

class DeltaFormFactors {
 public:
  // Throws std::invalid_argument unless resolution is even and at least 2.
  explicit DeltaFormFactors(int resolution);

  int resolution() const { return resolution_; }
  // Rows of a side face above the surface: 0 … side_rows() − 1 (= R/2).
  int side_rows() const { return half_; }

  // Top face cell (column, row), both in [0, R): not range-checked (the hot path).
  double top(int column, int row) const {
    const int a = fold(column), b = fold(row);
    return a >= b ? top_octant_[octant_index(a, b)] : top_octant_[octant_index(b, a)];
  }
  // Side face cell (column, row) above the surface: column in [0, R), row in [0, R/2); not
  // range-checked.
  double side(int column, int row) const {
    return side_quarter_[static_cast<std::size_t>(row) * half_ + fold(column)];
  }
  // Any face's cell: 0 for a side face's rows at or below the surface (row ≥ R/2). Throws
  // std::out_of_range for a column or row outside [0, R).
  double at(HemicubeFace face, int column, int row) const;

  // One full image row of a face expanded from the tables into out[0 … R−1] (zeros for the
  // rows of a side face below the surface): the summation of an item buffer reads it row by row.
  void expand_row(HemicubeFace face, int row, double* out) const;

  // 000 §6.4.1 evaluated directly at the cell centre, without the tables (for checks); the
  // tables hold exactly these values. Throws like the constructor and like at().
  static double evaluate(int resolution, HemicubeFace face, int column, int row);

  // Σ ΔF over every cell of the five faces (→ 1 as R grows).
  double total() const;
  // The number of values stored (h(h+1)/2 + h²) and the bytes they take.
  std::size_t stored_values() const { return top_octant_.size() + side_quarter_.size(); }
  std::size_t memory_bytes() const { return stored_values() * sizeof(double); }

 private:
  // |2·index + 1 − R| = 2·fold(index) + 1.
  int fold(int index) const { return index >= half_ ? index - half_ : half_ - 1 - index; }
  static std::size_t octant_index(int a, int b) {  // b ≤ a
    return static_cast<std::size_t>(a) * static_cast<std::size_t>(a + 1) / 2 + static_cast<std::size_t>(b);
  }

  int resolution_;
  int half_;
  std::vector<double> top_octant_;    // index a(a+1)/2 + b, 0 ≤ b ≤ a < h
  std::vector<double> side_quarter_;  // index row·h + a, row < h (above the surface), a < h
};

}  // namespace candela
