// Radiosity solvers: Gaussian elimination (000 eq. 6-9), Gauss-Seidel, progressive refinement
// with the ambient term (000 §6.6), substructuring (000 §6.7.1). See solvers.h.
#include "radiosity/solvers.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <memory>
#include <sstream>
#include <utility>

#include "util/memory.h"

namespace candela {
namespace {

using Index = Eigen::Index;

double channel_sum(const Color& c) {
  return c.r + c.g + c.b;
}

void require_square_source(const FormFactorSource& form_factors, std::size_t patch_count,
                           const char* solver) {
  if (form_factors.rows() != patch_count || form_factors.columns() != patch_count) {
    throw std::invalid_argument(
        std::string(solver) + ": form factors are " + std::to_string(form_factors.rows()) + "×" +
        std::to_string(form_factors.columns()) + " for " + std::to_string(patch_count) + " patches");
  }
}

double largest_component(const std::vector<Color>& values) {
  double largest = 0;
  for (const Color& value : values) {
    largest = std::max({largest, std::fabs(value.r), std::fabs(value.g), std::fabs(value.b)});
  }
  return largest;
}

// Divides by the largest radiosity when there is one (the solvers' relative measures).
double relative_to(double amount, double largest) {
  return largest > 0 ? amount / largest : amount;
}

std::string format_gibibytes(uint64_t bytes) {
  std::ostringstream text;
  text.precision(bytes >= (uint64_t{100} << 30) ? 0 : 1);
  text << std::fixed << static_cast<double>(bytes) / static_cast<double>(uint64_t{1} << 30) << " GiB";
  return text.str();
}

std::string format_number(double value) {
  std::ostringstream text;
  text << value;
  return text.str();
}

// The elements of each patch in index order, and the patch areas as sums of element areas.
struct PatchMembership {
  std::vector<std::vector<std::size_t>> elements;
  std::vector<double> areas;
};

PatchMembership patch_membership(const ElementSystem& elements, std::size_t patch_count) {
  PatchMembership membership;
  membership.elements.resize(patch_count);
  membership.areas.assign(patch_count, 0.0);
  for (std::size_t q = 0; q < elements.size(); ++q) {
    membership.elements[elements.patch[q]].push_back(q);
    membership.areas[elements.patch[q]] += elements.areas[q];
  }
  for (std::size_t i = 0; i < patch_count; ++i) {
    if (membership.elements[i].empty()) {
      throw std::invalid_argument("substructuring: patch " + std::to_string(i) +
                                  " has no elements (every patch needs at least one)");
    }
  }
  return membership;
}

}  // namespace

double radiosity_residual(const RadiositySystem& system, const FormFactorSource& form_factors,
                          const std::vector<Color>& radiosity) {
  system.validate();
  const std::size_t n = system.size();
  require_square_source(form_factors, n, "radiosity residual");
  if (radiosity.size() != n) {
    throw std::invalid_argument("radiosity residual: " + std::to_string(radiosity.size()) +
                                " radiosities for " + std::to_string(n) + " patches");
  }
  double largest_residual = 0;
  if (form_factors.is_dense()) {
    // Column-major F: the product F·B per channel runs down contiguous columns.
    const Eigen::MatrixXd& f = form_factors.matrix();
    Eigen::VectorXd channel(static_cast<Index>(n));
    for (int c = 0; c < 3; ++c) {
      for (std::size_t i = 0; i < n; ++i) channel(static_cast<Index>(i)) = radiosity[i][c];
      const Eigen::VectorXd gathered = f * channel;
      for (std::size_t i = 0; i < n; ++i) {
        const double equation = system.emission[i][c] +
                                system.reflectance[i][c] * gathered(static_cast<Index>(i));  // 000 eq. 6-7
        largest_residual = std::max(largest_residual, std::fabs(equation - radiosity[i][c]));
      }
    }
  } else {
    std::vector<double> row;
    for (std::size_t i = 0; i < n; ++i) {
      form_factors.row(i, row);
      Color gathered;
      for (std::size_t j = 0; j < n; ++j) gathered += row[j] * radiosity[j];
      const Color equation = system.emission[i] + system.reflectance[i] * gathered;  // 000 eq. 6-7
      for (int c = 0; c < 3; ++c) {
        largest_residual = std::max(largest_residual, std::fabs(equation[c] - radiosity[i][c]));
      }
    }
  }
  return relative_to(largest_residual, largest_component(radiosity));
}

// ---- Gaussian elimination ------------------------------------------------------------------

uint64_t gaussian_elimination_memory_bytes(std::size_t patch_count) {
  // Two n×n matrices of doubles (F, and I − diag(ρ)F factored in place) plus the permutation,
  // right-hand sides, solutions and radiosities: under 128 bytes a patch.
  const double n = static_cast<double>(patch_count);
  const double bytes = 2.0 * n * n * sizeof(double) + 128.0 * n;
  if (bytes >= static_cast<double>(std::numeric_limits<uint64_t>::max())) {
    return std::numeric_limits<uint64_t>::max();
  }
  return static_cast<uint64_t>(bytes);
}

uint64_t default_gaussian_elimination_memory_limit() {
  return memory_limit_bytes(0);
}

RadiositySolution solve_gaussian_elimination(const RadiositySystem& system,
                                             const FormFactorSource& form_factors,
                                             uint64_t memory_limit_bytes) {
  system.validate();
  const std::size_t n = system.size();
  require_square_source(form_factors, n, "Gaussian elimination");
  RadiositySolution solution;
  solution.iterations = 1;
  if (n == 0) return solution;

  // Refuse before reading a row or allocating a matrix.
  const uint64_t limit =
      memory_limit_bytes > 0 ? memory_limit_bytes : default_gaussian_elimination_memory_limit();
  const uint64_t required = gaussian_elimination_memory_bytes(n);
  if (required > limit) {
    throw SolverMemoryError(
        {},
        "radiosity: Gaussian elimination over " + std::to_string(n) + " patches needs about " +
            format_gibibytes(required) + " (the n×n form-factor matrix and its LU factors), more than the " +
            format_gibibytes(limit) +
            " allowed; set radiosity.solver to \"progressive\" (memory of order n, one form-factor row "
            "per step) or increase radiosity.patch_size to make fewer patches",
        required, limit);
  }

  const FormFactorSource dense_source =
      form_factors.is_dense() ? form_factors : FormFactorSource(form_factors.to_dense());
  const Eigen::MatrixXd& f = dense_source.matrix();
  solution.rows_computed = n;

  // 000 eq. 6-9: (I − diag(ρ)F) B = E, one system per primary color. Channels with the same
  // reflectances share one factorisation, solved together for their right-hand sides.
  solution.radiosity.assign(n, Color());
  Eigen::MatrixXd system_matrix(static_cast<Index>(n), static_cast<Index>(n));
  std::array<bool, 3> solved = {false, false, false};
  for (int c = 0; c < 3; ++c) {
    if (solved[c]) continue;
    std::vector<int> channels = {c};
    for (int other = c + 1; other < 3; ++other) {
      bool same_reflectance = !solved[other];
      for (std::size_t i = 0; i < n && same_reflectance; ++i) {
        same_reflectance = system.reflectance[i][other] == system.reflectance[i][c];
      }
      if (same_reflectance) channels.push_back(other);
    }

    Eigen::VectorXd reflectance(static_cast<Index>(n));
    Eigen::MatrixXd emission(static_cast<Index>(n), static_cast<Index>(channels.size()));
    for (std::size_t i = 0; i < n; ++i) {
      reflectance(static_cast<Index>(i)) = system.reflectance[i][c];
      for (std::size_t k = 0; k < channels.size(); ++k) {
        emission(static_cast<Index>(i), static_cast<Index>(k)) = system.emission[i][channels[k]];
      }
    }
    system_matrix.noalias() = -(reflectance.asDiagonal() * f);
    system_matrix.diagonal().array() += 1.0;
    const Eigen::PartialPivLU<Eigen::Ref<Eigen::MatrixXd>> lu(system_matrix);  // factored in place
    const double reciprocal_condition = lu.rcond();
    const Eigen::MatrixXd radiosity = lu.solve(emission);
    if (!(reciprocal_condition > 1e-13) || !radiosity.allFinite()) {
      throw std::runtime_error(
          "radiosity: Gaussian elimination: the system (I − ρF)B = E is singular (reciprocal condition " +
          format_number(reciprocal_condition) +
          "); a closed enclosure whose surfaces all reflect everything has no finite solution");
    }
    for (std::size_t k = 0; k < channels.size(); ++k) {
      for (std::size_t i = 0; i < n; ++i) {
        solution.radiosity[i][channels[k]] = radiosity(static_cast<Index>(i), static_cast<Index>(k));
      }
      solved[channels[k]] = true;
    }
  }
  solution.residual = radiosity_residual(system, dense_source, solution.radiosity);
  return solution;
}

// ---- Gauss-Seidel --------------------------------------------------------------------------

RadiositySolution solve_gauss_seidel(const RadiositySystem& system, const FormFactorSource& form_factors,
                                     double tolerance, std::size_t max_iterations,
                                     const GaussSeidelCallback& on_sweep) {
  system.validate();
  const std::size_t n = system.size();
  require_square_source(form_factors, n, "Gauss-Seidel");
  if (!(tolerance > 0) || !std::isfinite(tolerance)) {
    throw std::invalid_argument("Gauss-Seidel: tolerance " + std::to_string(tolerance) +
                                " (must be positive and finite)");
  }
  if (max_iterations == 0) throw std::invalid_argument("Gauss-Seidel: max_iterations must be at least 1");

  RadiositySolution solution;
  solution.radiosity = system.emission;  // B = E to start
  solution.converged = false;
  std::vector<Color>& b = solution.radiosity;
  std::vector<double> row;
  for (std::size_t sweep = 1; sweep <= max_iterations; ++sweep) {
    double largest_change = 0;
    for (std::size_t i = 0; i < n; ++i) {
      form_factors.row(i, row);
      ++solution.rows_computed;
      Color gathered;  // Σ_{j≠i} F_ij B_j, the latest values (in place)
      for (std::size_t j = 0; j < n; ++j) {
        if (j != i) gathered += row[j] * b[j];
      }
      const Color& rho = system.reflectance[i];
      for (int c = 0; c < 3; ++c) {
        // Row i of 000 eq. 6-9 solved for B_i: its diagonal entry is 1 − ρ_i F_ii.
        const double diagonal = 1.0 - rho[c] * row[i];
        if (!(diagonal > 0)) {
          throw std::invalid_argument("Gauss-Seidel: patch " + std::to_string(i) +
                                      " reflects all the light it sends to itself (ρ_i F_ii = " +
                                      std::to_string(rho[c] * row[i]) + ")");
        }
        const double updated = (system.emission[i][c] + rho[c] * gathered[c]) / diagonal;
        largest_change = std::max(largest_change, std::fabs(updated - b[i][c]));
        b[i][c] = updated;
      }
    }
    solution.iterations = sweep;
    solution.relative_change = relative_to(largest_change, largest_component(b));
    if (on_sweep) on_sweep(sweep, solution.relative_change, b);
    if (solution.relative_change <= tolerance) {
      solution.converged = true;
      break;
    }
  }
  solution.residual = radiosity_residual(system, form_factors, b);
  solution.rows_computed += n;
  return solution;
}

// ---- Progressive refinement ----------------------------------------------------------------

ProgressiveRefinement::ProgressiveRefinement(RadiositySystem system, FormFactorSource form_factors)
    : system_(std::move(system)), form_factors_(std::move(form_factors)) {
  system_.validate();
  const std::size_t n = system_.size();
  require_square_source(*form_factors_, n, "progressive refinement");
  // Every patch is its own one receiver.
  receivers_.patch.resize(n);
  for (std::size_t i = 0; i < n; ++i) receivers_.patch[i] = i;
  receivers_.areas = system_.areas;
  receivers_.reflectance = system_.reflectance;
  receivers_.emission = system_.emission;
  start();
}

ProgressiveRefinement::ProgressiveRefinement(RadiositySystem patches, ElementSystem elements,
                                             std::shared_ptr<const ElementToPatch> element_to_patch)
    : system_(std::move(patches)),
      receivers_(std::move(elements)),
      element_to_patch_(std::move(element_to_patch)) {
  system_.validate();
  receivers_.validate(system_.size());
  if (!element_to_patch_ || static_cast<std::size_t>(element_to_patch_->rows()) != receivers_.size() ||
      static_cast<std::size_t>(element_to_patch_->cols()) != system_.size()) {
    throw std::invalid_argument("progressive refinement: element-to-patch form factors are " +
                                (element_to_patch_ ? std::to_string(element_to_patch_->rows()) + "×" +
                                                         std::to_string(element_to_patch_->cols())
                                                   : std::string("missing")) +
                                " for " + std::to_string(receivers_.size()) + " elements and " +
                                std::to_string(system_.size()) + " patches");
  }
  start();
}

void ProgressiveRefinement::start() {
  radiosity_ = receivers_.emission;  // B = E
  unshot_ = system_.emission;        // ΔB = E: nothing shot yet
  for (std::size_t j = 0; j < size(); ++j) {
    total_area_ += system_.areas[j];
    emitted_flux_ += channel_sum(unshot_[j]) * system_.areas[j];
  }
  // 000 eq. 6-14: ρ_avg = Σ_q ρ_q A_q / Σ_j A_j.
  for (std::size_t q = 0; q < receivers_.size(); ++q)
    average_reflectance_ += receivers_.reflectance[q] * (receivers_.areas[q] / total_area_);
  update_totals();
}

void ProgressiveRefinement::restore(std::vector<Color> radiosity, std::vector<Color> unshot,
                                    std::size_t steps) {
  if (radiosity.size() != receivers_.size() || unshot.size() != size()) {
    throw std::invalid_argument("progressive refinement: a state of " + std::to_string(radiosity.size()) +
                                " receivers and " + std::to_string(unshot.size()) + " patches for " +
                                std::to_string(receivers_.size()) + " and " + std::to_string(size()));
  }
  radiosity_ = std::move(radiosity);
  unshot_ = std::move(unshot);
  steps_ = steps;
  update_totals();
}

void ProgressiveRefinement::update_totals() {
  unshot_flux_ = 0;
  next_shooter_ = size();
  double largest_unshot_flux = 0;
  for (std::size_t j = 0; j < size(); ++j) {
    const double patch_flux = channel_sum(unshot_[j]) * system_.areas[j];
    unshot_flux_ += patch_flux;
    if (patch_flux > largest_unshot_flux) {  // strict: the lowest index wins a tie
      largest_unshot_flux = patch_flux;
      next_shooter_ = j;
    }
  }
}

double ProgressiveRefinement::unshot_fraction() const {
  return emitted_flux_ > 0 ? unshot_flux_ / emitted_flux_ : 0.0;
}

template <typename FormFactorOf>
void ProgressiveRefinement::shoot(const Color& shot, FormFactorOf form_factor_of) {
  for (std::size_t q = 0; q < receivers_.size(); ++q) {
    const double form_factor = form_factor_of(q);  // F_qj
    if (form_factor <= 0) continue;
    const Color gain = receivers_.reflectance[q] * shot * form_factor;  // 000 eqs. 6-12, 6-13
    radiosity_[q] += gain;
    const std::size_t patch = receivers_.patch[q];
    unshot_[patch] += gain * (receivers_.areas[q] / system_.areas[patch]);  // area-weighted mean
  }
}

bool ProgressiveRefinement::step() {
  const std::size_t shooter = next_shooter_;
  if (shooter >= size()) return false;
  const Color shot = unshot_[shooter];
  unshot_[shooter] = Color();  // cleared first: what the shooter sends to itself stays unshot
  if (element_to_patch_) {
    const float* column = element_to_patch_->col(static_cast<Index>(shooter)).data();  // contiguous
    shoot(shot, [column](std::size_t q) { return static_cast<double>(column[q]); });
  } else {
    form_factors_->row(shooter, row_);  // F_j→i for every i: one hemicube at the shooter
    ++rows_computed_;
    const double shooter_area = system_.areas[shooter];
    // Reciprocity (000 eq. 6-5): F_ij = F_ji A_j / A_i.
    shoot(shot, [&](std::size_t i) { return row_[i] * shooter_area / system_.areas[i]; });
  }
  ++steps_;
  update_totals();
  return true;
}

ProgressiveRunResult ProgressiveRefinement::run(double threshold, std::size_t max_steps,
                                                const ProgressiveStepCallback& on_step,
                                                const ProgressiveCancelPredicate& cancelled) {
  if (!(threshold >= 0) || !std::isfinite(threshold)) {
    throw std::invalid_argument("progressive refinement: threshold " + std::to_string(threshold) +
                                " (must be a non-negative fraction of the emitted flux)");
  }
  ProgressiveRunResult result;
  while (unshot_fraction() > threshold && next_shooter_ < size() && result.steps < max_steps &&
         !(cancelled && cancelled(steps_))) {
    step();
    ++result.steps;
    if (on_step) on_step(steps_, unshot_fraction());
  }
  result.unshot_fraction = unshot_fraction();
  result.converged = result.unshot_fraction <= threshold;
  return result;
}

Color ProgressiveRefinement::ambient() const {
  // 000 §6.6.2: B_amb = 1/(1 − ρ_avg) · Σ_j ΔB_j A_j / Σ_k A_k, per channel.
  Color area_weighted_unshot;
  for (std::size_t j = 0; j < size(); ++j)
    area_weighted_unshot += unshot_[j] * (system_.areas[j] / total_area_);
  Color ambient;
  for (int c = 0; c < 3; ++c) {
    // A channel where every surface reflects everything has no finite series: no ambient there.
    if (average_reflectance_[c] < 1) ambient[c] = area_weighted_unshot[c] / (1 - average_reflectance_[c]);
  }
  return ambient;
}

Color ProgressiveRefinement::display_radiosity(std::size_t q, bool with_ambient) const {
  if (q >= receivers_.size()) {
    throw std::out_of_range("progressive refinement: receiver " + std::to_string(q) + " of " +
                            std::to_string(receivers_.size()));
  }
  if (!with_ambient) return radiosity_[q];
  return radiosity_[q] + receivers_.reflectance[q] * ambient();  // display only (000 §6.6.2)
}

std::vector<Color> ProgressiveRefinement::display_radiosities(bool with_ambient) const {
  std::vector<Color> display = radiosity_;
  if (with_ambient) {
    const Color ambient_radiosity = ambient();
    for (std::size_t q = 0; q < display.size(); ++q)
      display[q] += receivers_.reflectance[q] * ambient_radiosity;
  }
  return display;
}

// ---- Substructuring ------------------------------------------------------------------------

FormFactorSource element_to_patch_source(std::shared_ptr<const ElementToPatch> element_to_patch) {
  if (!element_to_patch) throw std::invalid_argument("substructuring: no element-to-patch form factors");
  const auto rows = static_cast<std::size_t>(element_to_patch->rows());
  const auto columns = static_cast<std::size_t>(element_to_patch->cols());
  return FormFactorSource(
      rows, columns,
      [element_to_patch = std::move(element_to_patch)](std::size_t q, std::vector<double>& row) {
        for (std::size_t j = 0; j < row.size(); ++j)
          row[j] = (*element_to_patch)(static_cast<Index>(q), static_cast<Index>(j));
      });
}

std::vector<Color> gather_element_radiosities(const ElementSystem& elements,
                                              const FormFactorSource& element_to_patch,
                                              const std::vector<Color>& patch_radiosity) {
  const std::size_t patch_count = patch_radiosity.size();
  elements.validate(patch_count);
  if (element_to_patch.rows() != elements.size() || element_to_patch.columns() != patch_count) {
    throw std::invalid_argument(
        "substructuring: element-to-patch form factors are " + std::to_string(element_to_patch.rows()) + "×" +
        std::to_string(element_to_patch.columns()) + " for " + std::to_string(elements.size()) +
        " elements and " + std::to_string(patch_count) + " patches");
  }
  std::vector<Color> element_radiosity(elements.size());
  tbb::enumerable_thread_specific<std::vector<double>> rows;
  tbb::parallel_for(std::size_t(0), elements.size(), [&](std::size_t q) {
    std::vector<double>& row = rows.local();
    element_to_patch.row(q, row);
    Color gathered;
    for (std::size_t j = 0; j < patch_count; ++j) gathered += row[j] * patch_radiosity[j];
    element_radiosity[q] = elements.emission[q] + elements.reflectance[q] * gathered;  // 000 eq. 6-16
  });
  return element_radiosity;
}

FormFactorSource patch_form_factors_from_elements(const ElementSystem& elements,
                                                  FormFactorSource element_to_patch) {
  const std::size_t patch_count = element_to_patch.columns();
  elements.validate(patch_count);
  if (element_to_patch.rows() != elements.size()) {
    throw std::invalid_argument("substructuring: element-to-patch form factors have " +
                                std::to_string(element_to_patch.rows()) + " rows for " +
                                std::to_string(elements.size()) + " elements");
  }
  auto membership = std::make_shared<const PatchMembership>(patch_membership(elements, patch_count));
  auto element_areas = std::make_shared<const std::vector<double>>(elements.areas);
  return FormFactorSource(patch_count, patch_count,
                          [membership, element_areas, element_to_patch = std::move(element_to_patch)](
                              std::size_t i, std::vector<double>& row) {
                            // 000 eq. 6-19: F_ij = (1/A_i) Σ_{q ∈ i} F_qj A_q.
                            std::vector<double> element_row;
                            for (const std::size_t q : membership->elements[i]) {
                              element_to_patch.row(q, element_row);
                              const double element_area = (*element_areas)[q];
                              for (std::size_t j = 0; j < row.size(); ++j)
                                row[j] += element_row[j] * element_area;
                            }
                            for (double& form_factor : row) form_factor /= membership->areas[i];
                          });
}

std::vector<Color> patch_radiosities_from_elements(const ElementSystem& elements,
                                                   const std::vector<Color>& element_radiosity,
                                                   std::size_t patch_count) {
  elements.validate(patch_count);
  if (element_radiosity.size() != elements.size()) {
    throw std::invalid_argument("substructuring: " + std::to_string(element_radiosity.size()) +
                                " element radiosities for " + std::to_string(elements.size()) + " elements");
  }
  const PatchMembership membership = patch_membership(elements, patch_count);
  std::vector<Color> patch_radiosity(patch_count);
  for (std::size_t i = 0; i < patch_count; ++i) {
    Color flux;
    for (const std::size_t q : membership.elements[i]) flux += element_radiosity[q] * elements.areas[q];
    patch_radiosity[i] = flux / membership.areas[i];  // B_i = (1/A_i) Σ_q B_q A_q (000 §6.7.1)
  }
  return patch_radiosity;
}

}  // namespace candela
