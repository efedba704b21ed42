// The classic radiosity problem (000 §6.1–6.3, SPEC §10), independent of how form factors are
// computed: patch areas A_i, diffuse reflectances ρ_i and emitted exitances E_i per RGB channel,
// and a source of form factors F_ij — the fraction of the power leaving patch i that arrives
// directly at patch j (000 eq. 6-4). The solvers in solvers.h find the radiosities B of
//
//   B_i = E_i + ρ_i Σ_j F_ij B_j                                   (000 eq. 6-7)
//
// Conventions: row i of a form-factor source holds F_i→j for every j (what a hemicube placed at
// patch i measures, 000 §6.4); reciprocity A_i F_ij = A_j F_ji (000 eq. 6-5); in a closed scene
// every row sums to 1 (000 eq. 6-6). F_ii may be non-zero (a concave patch sees itself).
// Radiosity, emission and flux are per channel; "flux" of a patch means B_i·A_i.
#pragma once

#include <Eigen/Dense>
#include <cmath>
#include <cstddef>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "math/vector.h"

namespace candela {

// Checks surfaces (patches or elements) given as parallel vectors; throws std::invalid_argument
// naming `owner` ("radiosity system"), the kind of surface ("patch") and the first bad index:
// vectors of different lengths, an area that is not positive and finite, a reflectance outside
// [0, 1], a negative or non-finite emission.
inline void validate_surfaces(const std::string& owner, const std::string& surface,
                              const std::vector<double>& areas, const std::vector<Color>& reflectance,
                              const std::vector<Color>& emission) {
  if (reflectance.size() != areas.size() || emission.size() != areas.size()) {
    throw std::invalid_argument(owner + ": " + std::to_string(areas.size()) + " areas, " +
                                std::to_string(reflectance.size()) + " reflectances and " +
                                std::to_string(emission.size()) + " emissions (they must match)");
  }
  for (std::size_t i = 0; i < areas.size(); ++i) {
    const std::string where = owner + ": " + surface + " " + std::to_string(i) + ": ";
    if (!(areas[i] > 0) || !std::isfinite(areas[i])) {
      throw std::invalid_argument(where + "area " + std::to_string(areas[i]) +
                                  " (must be positive and finite)");
    }
    for (int c = 0; c < 3; ++c) {
      if (!(reflectance[i][c] >= 0 && reflectance[i][c] <= 1)) {
        throw std::invalid_argument(where + "reflectance " + std::to_string(reflectance[i][c]) +
                                    " (must lie in [0, 1])");
      }
      if (!(emission[i][c] >= 0) || !std::isfinite(emission[i][c])) {
        throw std::invalid_argument(where + "emission " + std::to_string(emission[i][c]) +
                                    " (must be non-negative and finite)");
      }
    }
  }
}

// The patches of the scene: index i is the same in every vector.
struct RadiositySystem {
  std::vector<double> areas;       // A_i > 0
  std::vector<Color> reflectance;  // ρ_i per RGB channel, each in [0, 1]
  std::vector<Color> emission;     // E_i per RGB channel (exitance, ≥ 0)

  std::size_t size() const { return areas.size(); }

  // Throws std::invalid_argument naming the first bad patch (see validate_surfaces).
  void validate() const { validate_surfaces("radiosity system", "patch", areas, reflectance, emission); }
};

// The elements of a substructured scene (000 §6.7.1): element q lies on patch `patch[q]` and
// receives light from patches (elements are the smallest units whose radiosity is computed;
// patches shoot and gather). Index q is the same in every vector.
struct ElementSystem {
  std::vector<std::size_t> patch;  // owning patch per element
  std::vector<double> areas;       // A_q > 0
  std::vector<Color> reflectance;  // ρ_q, each in [0, 1]
  std::vector<Color> emission;     // E_q ≥ 0

  std::size_t size() const { return patch.size(); }
  // Throws std::invalid_argument for vectors of different lengths, a patch index ≥ patch_count,
  // or a bad area, reflectance or emission. (A patch may have no elements here; the area-weighted
  // means of solvers.h need at least one per patch and say so.)
  void validate(std::size_t patch_count) const {
    if (areas.size() != patch.size()) {
      throw std::invalid_argument("element system: " + std::to_string(patch.size()) + " patch indices for " +
                                  std::to_string(areas.size()) + " areas (they must match)");
    }
    for (std::size_t q = 0; q < patch.size(); ++q) {
      if (patch[q] >= patch_count) {
        throw std::invalid_argument("element system: element " + std::to_string(q) + " lies on patch " +
                                    std::to_string(patch[q]) + " of " + std::to_string(patch_count));
      }
    }
    validate_surfaces("element system", "element", areas, reflectance, emission);
  }
};

// The element rows F_qj, q an element, j a patch (000 §6.7.1: elements receive from patches), kept
// for a whole solve: float (4 bytes a form factor: the largest thing the solver keeps) and
// column-major, so that the column F_·j a shooting patch j reaches is contiguous.
using ElementToPatch = Eigen::MatrixXf;

// Computes row i of a form-factor matrix on demand (for instance a hemicube at patch i's
// centre). The row arrives sized to the source's column count and filled with zeros; the
// provider writes F_i→j into row[j] and must not resize it.
using FormFactorRowProvider = std::function<void(std::size_t i, std::vector<double>& row)>;

// Where the solvers get form factors: a dense matrix (row i = F_i→j) held once and shared by
// copies of the source, or a row provider that computes rows on demand so that memory stays of
// order n (000 §6.6: progressive refinement needs one row per step). Rectangular sources serve
// substructuring (rows = elements, columns = patches, 000 §6.7.1).
class FormFactorSource {
 public:
  explicit FormFactorSource(Eigen::MatrixXd matrix)
      : rows_(static_cast<std::size_t>(matrix.rows())),
        columns_(static_cast<std::size_t>(matrix.cols())),
        matrix_(std::make_shared<const Eigen::MatrixXd>(std::move(matrix))) {}

  FormFactorSource(std::size_t rows, std::size_t columns, FormFactorRowProvider provider)
      : rows_(rows), columns_(columns), provider_(std::move(provider)) {
    if (!provider_) throw std::invalid_argument("form-factor source: empty row provider");
  }

  std::size_t rows() const { return rows_; }
  std::size_t columns() const { return columns_; }
  bool is_dense() const { return matrix_ != nullptr; }

  // The dense matrix; throws std::logic_error for a row provider.
  const Eigen::MatrixXd& matrix() const {
    if (!matrix_) throw std::logic_error("form-factor source: no dense matrix (a row provider)");
    return *matrix_;
  }

  // Writes row i (F_i→j for every column j) into row, resized to columns(). Throws
  // std::out_of_range for a bad i, std::logic_error when a provider resizes the row, and
  // std::invalid_argument for a non-finite form factor.
  void row(std::size_t i, std::vector<double>& row) const {
    if (i >= rows_) {
      throw std::out_of_range("form-factor source: row " + std::to_string(i) + " of " +
                              std::to_string(rows_));
    }
    row.assign(columns_, 0.0);
    if (matrix_) {
      for (std::size_t j = 0; j < columns_; ++j) {
        row[j] = (*matrix_)(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j));
      }
    } else {
      provider_(i, row);
      if (row.size() != columns_) {
        throw std::logic_error("form-factor row provider resized row " + std::to_string(i) + " to " +
                               std::to_string(row.size()) + " entries (expected " + std::to_string(columns_) +
                               ")");
      }
    }
    for (std::size_t j = 0; j < columns_; ++j) {
      if (!std::isfinite(row[j])) {
        throw std::invalid_argument("form factor F[" + std::to_string(i) + "][" + std::to_string(j) +
                                    "] is not finite");
      }
    }
  }

  // The whole matrix: the held one, or every row from the provider in index order.
  Eigen::MatrixXd to_dense() const {
    if (matrix_) return *matrix_;
    Eigen::MatrixXd dense(static_cast<Eigen::Index>(rows_), static_cast<Eigen::Index>(columns_));
    std::vector<double> buffer;
    for (std::size_t i = 0; i < rows_; ++i) {
      row(i, buffer);
      for (std::size_t j = 0; j < columns_; ++j) {
        dense(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = buffer[j];
      }
    }
    return dense;
  }

 private:
  std::size_t rows_ = 0, columns_ = 0;
  std::shared_ptr<const Eigen::MatrixXd> matrix_;
  FormFactorRowProvider provider_;
};

}  // namespace candela
