// The transfer operator of the meshless method (seed 002 §5.2, SPEC §11), stored sparse:
//
//   R = Q S,  Q = diag(β(ṗ_j)) per channel,  S_jk = V(ṗ_k, ṗ_j) F(p_k, p_j) A_k          (5.6, 5.7)
//   F(p_k, p_j) = max(0, v_kj·p⃗_k) max(0, −v_kj·p⃗_j) / (π d²)                        (5.2)
//
// with d the distance between the sites, v_kj the direction from p_k to p_j and A_k the element's
// effective area. Close pairs: F·A_k of eq. 5.2 grows without bound as d → 0 (two sites on either
// side of a room's corner, which the spacing Δ does not keep apart since their site distance is
// infinite), so S_jk is clamped at 1 — no element passes a site more than all it sends. (A disc
// form factor cos cos A/(πd² + A) also stays bounded, but it undercounts near neighbours on curved
// surfaces: 2.3 % low in the sphere furnace against 0.5 % for eq. 5.2.) A row whose entries add up
// past 1 — more than the receiver's hemisphere, which happens only near such corners — is scaled
// back to 1.
// V is a shadow ray between the sites, each end moved off its surface along its normal.
//
// The solution (002 §5.2.4): λ ← η + Q S λ, per channel, from λ = η, until no coefficient changes by
// more than tolerance × the largest; λ are the coefficients of the radiosity (exitance) in the
// basis, η those of what is emitted and directly reflected.
#pragma once

#include <Eigen/SparseCore>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "math/vector.h"
#include "meshless/site.h"

namespace candela {

class Cluster;
class ProgressReporter;
class Scene;

struct TransferMatrix {
  Eigen::SparseMatrix<float, Eigen::RowMajor, int32_t> S;  // n × n
  std::size_t entries() const { return static_cast<std::size_t>(S.nonZeros()); }
  double density() const;     // entries / n²
  std::size_t bytes() const;  // values, column indices and row offsets
  double seconds = 0;         // to compute
  uint64_t visibility_rays = 0;
};

// S for the sites with effective areas A_k; the scene's accelerator answers visibility. Rows in
// parallel, each by one thread into its own place: the result does not depend on the thread count.
// max_entries refuses (std::invalid_argument naming the spacing) before more would be kept.
// With a cluster of several ranks the rows are computed across them and every rank gets all of
// S, the same as one process computes (issue 11).
// progress, when given, is advanced once per row (rank 0 counts every rank's rows).
TransferMatrix compute_transfer_matrix(const Scene& scene, const std::vector<Site>& sites,
                                       const std::vector<double>& effective_area, std::size_t max_entries = 0,
                                       Cluster* cluster = nullptr, ProgressReporter* progress = nullptr);

struct TransferSolution {
  std::vector<Color> lambda;
  std::size_t iterations = 0;
  bool converged = false;
  bool diverged = false;    // λ grew past 10¹² × max η or overflowed: the iteration stopped
  double final_change = 0;  // the last iteration's largest change over the largest λ
};

// λ = η + Q S λ by the iteration of 002 §5.2.4 (Q = albedo); progress, when given, advances in
// per mille of convergence (the change's way down to the tolerance, on a log scale). Throws
// std::invalid_argument for mismatched sizes.
TransferSolution solve_transfer(const TransferMatrix& transfer, const std::vector<Color>& albedo,
                                const std::vector<Color>& eta, double tolerance, std::size_t max_iterations,
                                ProgressReporter* progress = nullptr);

}  // namespace candela
