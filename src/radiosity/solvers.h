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
//   n), or to every element with the elements' own rows (substructuring, 000 §6.7.1), until the
//   unshot flux is below a fraction of the emitted flux (default 0.1%), with the ambient term of
//   000 §6.6.2 for display.
// - Substructuring (000 §6.7.1): element radiosities gathered from the patch solution
//   (000 eq. 6-16), patch form factors as area-weighted means of element rows (000 eq. 6-19),
//   patch radiosities as area-weighted means of element radiosities.
//
// Everything is deterministic: the same input gives bit-identical output. All is sequential but
// gather_element_radiosities, whose elements are gathered in parallel, each into its own place.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "math/vector.h"
#include "radiosity/radiosity_system.h"
#include "util/error.h"

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
// settings that fix it: radiosity.solver (use "progressive") and radiosity.patch_size. A
// setting that asks too much is bad input — an InputError (exit 2) at the setting's location.
class SolverMemoryError : public InputError {
 public:
  SolverMemoryError(const SourceLocation& location, const std::string& message, uint64_t required_bytes,
                    uint64_t limit_bytes)
      : InputError(location, message), required_bytes_(required_bytes), limit_bytes_(limit_bytes) {}
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

// Called after every sweep with the sweep number (1-based), its largest relative change and the
// radiosities then.
using GaussSeidelCallback =
    std::function<void(std::size_t sweep, double relative_change, const std::vector<Color>& radiosity)>;

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
// seed counts "after 1, 2, 20 and 100 iterations") and the unshot fraction then: take snapshots,
// advance progress bars and write checkpoints here.
using ProgressiveStepCallback = std::function<void(std::size_t step, double unshot_fraction)>;
// Asked before every step with the number of steps taken so far; true stops the run there (Ctrl-C).
using ProgressiveCancelPredicate = std::function<bool(std::size_t steps)>;

struct ProgressiveRunResult {
  std::size_t steps = 0;       // steps taken by this run
  double unshot_fraction = 0;  // on return
  bool converged = false;      // unshot_fraction ≤ threshold
};

// 000 §6.6: the patch j with the largest unshot flux ΔB_j·A_j shoots its unshot radiosity to the
// receivers. A receiver q lies on a patch p(q) (a patch is its own one receiver, or, with
// substructuring (000 §6.7.1), an element of it), receives
//   ΔRad_q = ρ_q ΔB_j F_qj                                        (000 eqs. 6-12, 6-13)
// and B_q += ΔRad_q, ΔB_p(q) += ΔRad_q A_q / A_p(q): the unshot radiosity of q's patch grows by the
// area-weighted mean of its receivers' gains. Where F_qj comes from depends on the receivers:
//   patches   row j of a square source (F_j→i, a hemicube at the shooter; one row per step,
//             memory of order n) and reciprocity F_ij = F_ji A_j / A_i (000 eq. 6-5);
//   elements  column j of the elements' own rows F_qj (element_to_patch: a hemicube at every
//             element over the patches, computed once). Each such row sums to 1 in a closed scene,
//             which the shooter's hemicube with reciprocity does not give elements near the
//             shooter (a furnace then shows ±17%).
// Flux means ΔB·A summed over the channels. Sequential and deterministic.
class ProgressiveRefinement {
 public:
  // Patches receive. Starts from B = ΔB = E. The source must be square; only rows of shooting
  // patches are read. Throws std::invalid_argument for a bad system or source shape.
  ProgressiveRefinement(RadiositySystem system, FormFactorSource form_factors);
  // The elements receive (000 §6.7.1). Starts from B_q = E_q and ΔB_j = E_j. element_to_patch
  // has one row per element and one column per patch. Throws std::invalid_argument for a bad
  // system, bad elements, or rows of the wrong shape.
  ProgressiveRefinement(RadiositySystem patches, ElementSystem elements,
                        std::shared_ptr<const ElementToPatch> element_to_patch);

  std::size_t size() const { return system_.size(); }  // patches
  const RadiositySystem& system() const { return system_; }
  const std::vector<Color>& radiosity() const { return radiosity_; }      // B per receiver
  const std::vector<Color>& unshot_radiosity() const { return unshot_; }  // ΔB per patch

  // Continues from a saved state (a checkpoint) instead of B = ΔB = E: B per receiver,
  // ΔB per patch and the steps that led there. Throws std::invalid_argument, naming both sizes,
  // when the state does not fit.
  void restore(std::vector<Color> radiosity, std::vector<Color> unshot, std::size_t steps);

  // Σ_j ΔB_j·A_j and Σ_j E_j·A_j over the patches, summed over the channels.
  double unshot_flux() const { return unshot_flux_; }
  double emitted_flux() const { return emitted_flux_; }
  // unshot_flux / emitted_flux (0 when nothing is emitted).
  double unshot_fraction() const;

  // The patch that step() shoots next: the largest unshot flux ΔB_j·A_j (channels summed), the
  // lowest index among equals; size() when nothing is left to shoot.
  std::size_t next_shooter() const { return next_shooter_; }

  // One shot from next_shooter() = j, with ΔB_j cleared first so that light j sends to itself
  // (F_jj with patch receivers) stays unshot. Returns false (and does nothing) when no unshot
  // flux is left.
  bool step();

  // Steps until unshot_fraction() ≤ threshold, max_steps steps have been taken by this call,
  // nothing is left to shoot, or cancelled (asked only when another step would follow) says to
  // stop. Throws std::invalid_argument for a negative or non-finite threshold.
  ProgressiveRunResult run(double threshold = 0.001,
                           std::size_t max_steps = std::numeric_limits<std::size_t>::max(),
                           const ProgressiveStepCallback& on_step = {},
                           const ProgressiveCancelPredicate& cancelled = {});

  // The ambient radiosity of 000 §6.6.2, per channel:
  //   ρ_avg = Σ_q ρ_q A_q / Σ_j A_j                                 (000 eq. 6-14)
  //   R = 1 + ρ_avg + ρ_avg² + … = 1 / (1 − ρ_avg)                 (000 eq. 6-15)
  //   B_amb = R Σ_j ΔB_j F^est_j  with  F^est_j = A_j / Σ_k A_k
  // It vanishes as the solution converges (ΔB → 0). In a channel where every surface reflects
  // everything (ρ_avg = 1) the series diverges, and that channel has no ambient term (0).
  Color ambient() const;

  // What to display for receiver q: B_q, plus ρ_q·B_amb with the ambient term (000 §6.6.2: for
  // display only, never fed back into the solution).
  Color display_radiosity(std::size_t q, bool with_ambient) const;
  std::vector<Color> display_radiosities(bool with_ambient) const;

  // Statistics: steps taken (with those restored), rows read from a patch source.
  std::size_t steps() const { return steps_; }
  std::size_t rows_computed() const { return rows_computed_; }

 private:
  // B = E per receiver, ΔB = E per patch, the emitted flux and ρ_avg (000 eq. 6-14).
  void start();
  // Recomputes the unshot flux and the next shooter in one pass over the patches.
  void update_totals();
  // Gives every receiver q its share of `shot`, the unshot radiosity of the shooting patch j,
  // with F_qj = form_factor_of(q).
  template <typename FormFactorOf>
  void shoot(const Color& shot, FormFactorOf form_factor_of);

  RadiositySystem system_;  // the patches
  ElementSystem receivers_;
  std::optional<FormFactorSource> form_factors_;            // patch receivers: the shooters' rows
  std::shared_ptr<const ElementToPatch> element_to_patch_;  // element receivers: their own rows
  std::vector<Color> radiosity_, unshot_;
  std::vector<double> row_;    // the shooter's form factors, reused every step
  double total_area_ = 0;      // Σ_j A_j over the patches
  Color average_reflectance_;  // ρ_avg per channel (000 eq. 6-14)
  double unshot_flux_ = 0, emitted_flux_ = 0;
  std::size_t next_shooter_ = 0;
  std::size_t steps_ = 0, rows_computed_ = 0;
};

// ---- Substructuring (000 §6.7.1) ---------------------------------------------------------

// The element rows as a form-factor source (rows = elements, columns = patches) that reads the
// float matrix in place.
FormFactorSource element_to_patch_source(std::shared_ptr<const ElementToPatch> element_to_patch);

// Element radiosities from the patch solution (000 eq. 6-16):
//   B_q = E_q + ρ_q Σ_j F_qj B_j
// element_to_patch: rows = elements, columns = patches (F_q→j, e.g. a hemicube at the element's
// centre that sees patches). Reads every element row once, the elements in parallel (a row
// provider must be safe to call from several threads). Throws std::invalid_argument for
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
