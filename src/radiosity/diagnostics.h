// What the radiosity solve reports about its form factors (render --stats, SPEC §10): the row
// sums (000 eq. 6-6: 1 in a closed scene) and reciprocity (000 eq. 6-5).
#pragma once

#include <Eigen/Dense>
#include <nlohmann/json.hpp>
#include <vector>

#include "radiosity/radiosity_mesh.h"

namespace candela {

// A row that sees nothing at all (a face lying on another, like a box's bottom on the floor, whose
// hemicube sees only the floor's back) sums to less than this: it is hidden, not open.
inline constexpr double kHiddenRowSum = 1e-6;

// Row sums of the form-factor rows, summarised: {"rows", "hidden_rows"} and, over the rows that
// are not hidden, "min", "mean" and "max".
nlohmann::json row_sum_facts(const std::vector<double>& row_sums);

// Reciprocity (000 eq. 6-5) of patch form factors F_ij, measured over every pair: the
// transfer-weighted mean Σ|A_i F_ij − A_j F_ji| / Σ(A_i F_ij + A_j F_ji) and the largest
// mismatch relative to the largest transfer.
struct Reciprocity {
  bool measured = false;
  double mean_error = 0, max_error = 0;
};

Reciprocity measure_reciprocity(const std::vector<RadiositySurface>& patches,
                                const Eigen::MatrixXd& patch_rows);

}  // namespace candela
