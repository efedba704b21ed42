// Solvers of the classic radiosity equation B_i = E_i + ρ_i Σ_j F_ij B_j (000 eq. 6-7, SPEC §10),
// one RGB channel at a time in effect, for any form-factor source (radiosity_system.h):
//
// - solve_gaussian_elimination: the full system (I − diag(ρ)F) B = E of 000 eq. 6-9 by LU
//   factorisation with partial pivoting (Eigen). Memory of order n², time of order n³; refuses,
//   before allocating anything, a system whose matrices would not fit (SolverMemoryError).
// - solve_gauss_seidel: the same system by Gauss-Seidel sweeps in place, until the largest change
//   of a sweep is below tolerance × max B.
// - ProgressiveRefinement: 000 §6.6 — shoot the unshot radiosity of the patch with the largest
//   unshot flux ΔB_j·A_j to every patch with one row of form factors per step (memory of order
//   n), until the unshot flux is below a fraction of the emitted flux (default 0.1%), with the
//   ambient term of 000 §6.6.2 for display.
// - Substructuring (000 §6.7.1): element radiosities gathered from the patch solution
//   (000 eq. 6-16), patch form factors as area-weighted means of element rows (000 eq. 6-19),
//   patch radiosities as area-weighted means of element radiosities.
//
// Everything is sequential and deterministic: the same input gives bit-identical output.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "math/vector.h"
#include "radiosity/radiosity_system.h"

namespace candela {

// What a solver returns besides the radiosities.
struct RadiositySolution {
  std::vector<Color> radiosity;   // B_i per channel
  std::size_t iterations = 0;     // Gauss-Seidel sweeps; 1 for Gaussian elimination
  double relative_change = 0;     // Gauss-Seidel: the last sweep's largest |ΔB| / max B
  double residual = 0;            // max over i, channels of |E_i + ρ_i Σ_j F_ij B_j − B_i| / max B
  bool converged = true;          // Gauss-Seidel: relative_change ≤ tolerance
  std::size_t rows_computed = 0;  // form-factor rows read from the source
};

// The largest equation residual |E_i + ρ_i Σ_j F_ij B_j − B_i| over patches and channels,
// relative to the largest radiosity (absolute when every B is 0). Reads every row once.
double radiosity_residual(const RadiositySystem& system, const FormFactorSource& form_factors,
                          const std::vector<Color>& radiosity);

// ---- Gaussian elimination (000 eq. 6-9) ----------------------------------------------------

// Thrown when the full-matrix solver would need more memory than allowed. The message names the
// settings that fix it: radiosity.solver (use "progressive") and radiosity.patch_size.
class SolverMemoryError : public std::invalid_argument {
 public:
  SolverMemoryError(const std::string& message, uint64_t required_bytes, uint64_t limit_bytes)
      : std::invalid_argument(message), required_bytes_(required_bytes), limit_bytes_(limit_bytes) {}
  uint64_t required_bytes() const { return required_bytes_; }
  uint64_t limit_bytes() const { return limit_bytes_; }

 private:
  uint64_t required_bytes_, limit_bytes_;
};

// Bytes the Gaussian-elimination solver holds for n patches: the n×n form-factor matrix, the
// n×n system matrix factored in place into its LU factors, and O(n) vectors.
uint64_t gaussian_elimination_memory_bytes(std::size_t patch_count);

// Half the physical memory (MemTotal of /proc/meminfo) when it can be read, 8 GiB otherwise.
uint64_t default_gaussian_elimination_memory_limit();

// Solves (I − diag(ρ)F) B = E per channel by LU with partial pivoting; one factorisation serves
// every channel whose reflectances equal an earlier channel's (grey surfaces: one in all). A row
// provider is read into a dense matrix first (n rows). memory_limit_bytes = 0 uses
// default_gaussian_elimination_memory_limit(). Throws SolverMemoryError (before reading any row)
// when gaussian_elimination_memory_bytes(n) exceeds the limit, std::invalid_argument for a bad
// system or a form-factor source of the wrong shape, std::runtime_error for a singular system
// (a closed enclosure of perfect reflectors).
RadiositySolution solve_gaussian_elimination(const RadiositySystem& system,
                                             const FormFactorSource& form_factors,
                                             uint64_t memory_limit_bytes = 0);

// ---- Gauss-Seidel ------------------------------------------------------------------------

// Called after every sweep with the sweep number (1-based) and its largest relative change.
using GaussSeidelCallback = std::function<void(std::size_t sweep, double relative_change)>;

// Gauss-Seidel on 000 eq. 6-9: for i = 0 … n−1, in place,
//   B_i ← (E_i + ρ_i Σ_{j≠i} F_ij B_j) / (1 − ρ_i F_ii),
// the fixed point of B_i = E_i + ρ_i Σ_j F_ij B_j (000 eq. 6-7) solved for its own term, starting
// from B = E. Stops when a sweep's largest change (over patches and channels) is at most
// tolerance × max B, or after max_iterations sweeps (converged = false). Every sweep reads every
// row once: with a row provider that recomputes all rows each sweep (memory O(n)); pass a dense
// matrix to compute them once. The final residual costs one more pass over the rows. Throws
// std::invalid_argument for a bad system, source shape, tolerance ≤ 0 or max_iterations = 0, and
// for a patch with ρ_i F_ii ≥ 1.
RadiositySolution solve_gauss_seidel(const RadiositySystem& system, const FormFactorSource& form_factors,
                                     double tolerance = 1e-6, std::size_t max_iterations = 1000,
                                     const GaussSeidelCallback& on_sweep = {});

// ---- Progressive refinement (000 §6.6) ---------------------------------------------------

// Called after every step with the number of steps taken so far (1 after the first shot, as the
// seed counts "after 1, 2, 20 and 100 iterations") and the unshot fraction then: take snapshots
// and advance progress bars here.
using ProgressiveStepCallback = std::function<void(std::size_t step, double unshot_fraction)>;

struct ProgressiveRunResult {
  std::size_t steps = 0;       // steps taken by this run
  double unshot_fraction = 0;  // on return
  bool converged = false;      // unshot_fraction ≤ threshold
};

class ProgressiveRefinement {
 public:
  // Starts from B = ΔB = E. The source must be square; only rows of shooting patches are read.
  // Throws std::invalid_argument for a bad system or source shape.
  ProgressiveRefinement(RadiositySystem system, FormFactorSource form_factors);

  std::size_t size() const { return system_.size(); }
  const RadiositySystem& system() const { return system_; }
  const std::vector<Color>& radiosity() const { return radiosity_; }      // B
  const std::vector<Color>& unshot_radiosity() const { return unshot_; }  // ΔB

  // Σ_i ΔB_i·A_i and Σ_i E_i·A_i, summed over the channels.
  double unshot_flux() const { return unshot_flux_; }
  double emitted_flux() const { return emitted_flux_; }
  // unshot_flux / emitted_flux (0 when nothing is emitted).
  double unshot_fraction() const;

  // The patch that step() shoots next: the largest unshot flux ΔB_j·A_j (channels summed), the
  // lowest index among equals; size() when nothing is left to shoot.
  std::size_t next_shooter() const { return next_shooter_; }

  // One shot from next_shooter() = j (000 eqs. 6-12, 6-13): reads row j (F_j→i) and, with
  // ΔB_j cleared first so that light j sends to itself (F_jj) stays unshot, for every patch i
  //   ΔRad = ρ_i ΔB_j F_ji A_j / A_i;  B_i += ΔRad;  ΔB_i += ΔRad.
  // Returns false (and does nothing) when no unshot flux is left.
  bool step();

  // Steps until unshot_fraction() ≤ threshold, max_steps steps have been taken by this call, or
  // nothing is left to shoot. Throws std::invalid_argument for a negative or non-finite threshold.
  ProgressiveRunResult run(double threshold = 0.001,
                           std::size_t max_steps = std::numeric_limits<std::size_t>::max(),
                           const ProgressiveStepCallback& on_step = {});

  // The ambient radiosity of 000 §6.6.2, per channel:
  //   ρ_avg = Σ_j ρ_j A_j / Σ_j A_j                                 (000 eq. 6-14)
  //   R = 1 + ρ_avg + ρ_avg² + … = 1 / (1 − ρ_avg)                 (000 eq. 6-15)
  //   B_amb = R Σ_i ΔB_i F^est_i  with  F^est_i = A_i / Σ_k A_k
  // It vanishes as the solution converges (ΔB → 0). Throws std::domain_error when ρ_avg = 1 in
  // some channel while unshot radiosity remains there (the series diverges).
  Color ambient() const;

  // What to display for patch i: B_i, plus ρ_i·B_amb with the ambient term (000 §6.6.2: for
  // display only, never fed back into the solution).
  Color display_radiosity(std::size_t i, bool with_ambient) const;
  std::vector<Color> display_radiosities(bool with_ambient) const;

  // Statistics.
  std::size_t steps() const { return steps_; }
  std::size_t rows_computed() const { return rows_computed_; }

 private:
  // Recomputes the unshot flux, the sums of the ambient term and the next shooter in one pass.
  void update_totals();

  RadiositySystem system_;
  FormFactorSource form_factors_;
  std::vector<Color> radiosity_, unshot_;
  std::vector<double> row_;  // the shooter's form factors, reused every step
  double total_area_ = 0;
  Color average_reflectance_;   // ρ_avg per channel (000 eq. 6-14)
  Color area_weighted_unshot_;  // Σ_i ΔB_i A_i / Σ_k A_k per channel
  double unshot_flux_ = 0, emitted_flux_ = 0;
  std::size_t next_shooter_ = 0;
  std::size_t steps_ = 0, rows_computed_ = 0;
};

// How far a progressive run has come on a log scale, for progress bars: 0 at unshot fraction 1,
// 1 at the threshold (log(fraction) / log(threshold), clamped to [0, 1]); 1 when threshold ≥ 1.
double progressive_convergence_progress(double unshot_fraction, double threshold);

// ---- Substructuring (000 §6.7.1) ---------------------------------------------------------

// The elements of a substructured scene: element q lies on patch `patch[q]` and receives light
// from patches (elements are the smallest units whose radiosity is computed; patches shoot and
// gather). Index q is the same in every vector.
struct ElementSystem {
  std::vector<std::size_t> patch;  // owning patch per element
  std::vector<double> areas;       // A_q > 0
  std::vector<Color> reflectance;  // ρ_q, each in [0, 1]
  std::vector<Color> emission;     // E_q ≥ 0

  std::size_t size() const { return patch.size(); }
  // Throws std::invalid_argument for vectors of different lengths, a patch index ≥ patch_count,
  // or a bad area, reflectance or emission. (A patch may have no elements here; the area-weighted
  // means below need at least one per patch and say so.)
  void validate(std::size_t patch_count) const;
};

// Element radiosities from the patch solution (000 eq. 6-16):
//   B_q = E_q + ρ_q Σ_j F_qj B_j
// element_to_patch: rows = elements, columns = patches (F_q→j, e.g. a hemicube at the element's
// centre that sees patches). Reads every element row once. Throws std::invalid_argument for
// mismatched sizes.
std::vector<Color> gather_element_radiosities(const ElementSystem& elements,
                                              const FormFactorSource& element_to_patch,
                                              const std::vector<Color>& patch_radiosity);

// Patch form factors from element rows (000 eq. 6-19), patch i's area being the sum of its
// elements' areas:
//   F_ij = (1/A_i) Σ_{q ∈ i} F_qj A_q
// as a square row-provider source over the patches (the columns of element_to_patch): row i reads
// the rows of patch i's elements in index order (call to_dense() for the full matrix). Throws
// std::invalid_argument for mismatched sizes or a patch without elements.
FormFactorSource patch_form_factors_from_elements(const ElementSystem& elements,
                                                  FormFactorSource element_to_patch);

// Patch radiosities as area-weighted means of their elements' (000 §6.7.1, before eq. 6-17):
//   B_i = (1/A_i) Σ_{q ∈ i} B_q A_q
// Throws std::invalid_argument for mismatched sizes or a patch without elements.
std::vector<Color> patch_radiosities_from_elements(const ElementSystem& elements,
                                                   const std::vector<Color>& element_radiosity,
                                                   std::size_t patch_count);

}  // namespace candela
