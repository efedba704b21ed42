#include "radiosity/solve.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstddef>
#include <memory>
#include <stdexcept>
#include <vector>

#include "distributed/cluster.h"
#include "radiosity/adaptive_subdivision.h"
#include "radiosity/diagnostics.h"
#include "radiosity/first_shot.h"
#include "radiosity/form_factor_memory.h"
#include "radiosity/form_factor_rows.h"
#include "radiosity/hierarchical_radiosity.h"
#include "radiosity/solvers.h"
#include "scene/scene.h"
#include "util/cancellation.h"
#include "util/progress.h"
#include "util/statistics.h"

namespace candela {
namespace {

// What the elements' radiosities came to.
struct ElementSolution {
  std::vector<Color> radiosity;  // B_q: what adaptive subdivision compares
  std::vector<Color> displayed;  // B_q, plus ρ_q·B_amb with the ambient term (000 §6.6.2)
  std::size_t steps = 0;
  double unshot_fraction = 0;
  bool converged = true;
};

// 000 §6.6 with substructuring (000 §6.7.1): patches shoot, elements receive, from B = E or the
// checkpoint's state, with the progress bar, checkpoints and Ctrl-C.
ElementSolution shoot_progressively(
    const RadiosityMesh& mesh, const ElementRows& rows, const RadiositySettings& settings,
    ProgressReporter& progress, ProgressiveCheckpointing* checkpointing, Cluster* cluster,
    const std::function<void(const ProgressiveRefinement&, std::size_t steps, double fraction)>& observe) {
  ProgressiveRefinement refinement(mesh.patch_system(), mesh.element_system(), rows.form_factors);
  if (checkpointing && checkpointing->resume) {
    const RadiosityCheckpoint& state = *checkpointing->resume;
    if (state.radiosity.size() != mesh.elements.size() || state.unshot.size() != mesh.patches.size())
      throw std::invalid_argument(fmt::format(
          "the checkpoint holds {} elements and {} patches, this mesh {} and {}", state.radiosity.size(),
          state.unshot.size(), mesh.elements.size(), mesh.patches.size()));
    refinement.restore(state.radiosity, state.unshot, static_cast<std::size_t>(state.steps));
  }
  const auto sealed_state = [&] {
    return seal_radiosity_checkpoint({checkpointing->fingerprint, refinement.steps(), refinement.radiosity(),
                                      refinement.unshot_radiosity()});
  };
  const auto on_step = [&](std::size_t steps, double fraction) {
    const auto done = static_cast<uint64_t>(1000 * convergence_progress(fraction, settings.threshold));
    progress.set_detail(fmt::format("unshot {:.3g}% after {} steps", 100 * fraction, steps));
    progress.advance_to(done);
    if (checkpointing) checkpointing->schedule->between_steps(sealed_state);
    if (observe) observe(refinement, steps, fraction);
  };
  // Ctrl-C: the solution so far (several ranks agree every 256 shots, so they shoot alike; a shot
  // takes microseconds, an agreement between nodes tens of them).
  const auto cancelled = [&](std::size_t steps) {
    return cluster ? steps % 256 == 0 && cancelled_anywhere(*cluster) : cancel_requested();
  };
  const auto max_steps = static_cast<std::size_t>(settings.max_steps);  // with the steps resumed
  const ProgressiveRunResult run =
      refinement.run(settings.threshold, max_steps > refinement.steps() ? max_steps - refinement.steps() : 0,
                     on_step, cancelled);
  // The final state: a later run goes on from it (after Ctrl-C, or with a lower threshold).
  if (checkpointing) checkpointing->schedule->finish(sealed_state);
  ElementSolution solution;
  solution.radiosity = refinement.radiosity();
  solution.displayed = refinement.display_radiosities(settings.ambient);
  solution.steps = refinement.steps();
  solution.unshot_fraction = run.unshot_fraction;
  solution.converged = run.converged;
  return solution;
}

// Refused before the mesh is built (it can take gigabytes itself): the fewest patches and elements
// these sizes can give, and what their form factors would take.
void refuse_before_meshing(const Scene& scene, const RadiositySettings& settings,
                           const RadiosityMeshSettings& mesh_settings, const std::string& fewer) {
  const bool progressive = settings.solver == RadiositySolver::progressive;
  const RadiosityMeshEstimate least = estimate_radiosity_mesh(scene, mesh_settings);
  const double element_bytes = least.elements * least.patches * sizeof(float);
  const double patch_bytes = progressive ? 0.0
                                         : least.patches * least.patches * sizeof(double) *
                                               (settings.solver == RadiositySolver::gaussian ? 3 : 1);
  const double bytes = std::min(element_bytes + patch_bytes, 1.8e19);
  check_form_factor_memory(
      static_cast<uint64_t>(bytes), settings,
      fmt::format("a mesh of at least {:.0f} patches and {:.0f} elements", least.patches, least.elements),
      progressive ? fewer : "use radiosity.solver \"progressive\", or " + fewer);
}

// The seconds of the solve's phases that solve_facts reports beside the result's own.
struct SolveSeconds {
  double form_factors = 0, first_shot = 0;
};

// What the solve measured: the "radiosity" facts of render --stats without the display's. row_sums
// are the rows the solver read (element rows for progressive, patch rows for the direct solvers,
// which report their element rows too).
nlohmann::json solve_facts(const Scene& scene, const RadiositySettings& settings,
                           const RadiositySolveResult& result, const SolveSeconds& times,
                           const Reciprocity& reciprocity, const std::vector<double>& row_sums,
                           const std::vector<double>* element_row_sums, bool form_factors_complete) {
  const bool progressive = settings.solver == RadiositySolver::progressive;
  nlohmann::json out = {
      {"solver", kRadiositySolverNames.name(settings.solver)},
      {"form_factors", kRadiosityFormFactorNames.name(settings.form_factors)},
      {"hemicube_resolution", settings.hemicube_resolution},
      {"patches", result.mesh.patches.size()},
      {"elements", result.mesh.elements.size()},
      {"patch_size", result.mesh.patch_size},
      {"element_size", result.mesh.element_size},
      {"steps", result.steps},
      {"converged", result.converged},
      {"unshot_fraction", result.unshot_fraction},
      {"subdivision_passes", result.subdivision_passes},
      {"form_factor_rows", result.form_factor_rows},
      {"form_factors_computed", result.form_factors},
      {"form_factors_per_second",
       times.form_factors > 0 ? static_cast<double>(result.form_factors) / times.form_factors : 0.0},
      {"form_factor_memory_mib", static_cast<double>(result.form_factor_bytes) / 1048576.0},
      {"mesh_seconds", result.mesh_seconds},
      {"solve_seconds", result.solve_seconds},
      {"form_factor_seconds", times.form_factors},
      {"scene_lights", scene.lights.size()},
      {"first_shot_seconds", times.first_shot}};
  if (reciprocity.measured) {  // progressive: up to 2,048 patches
    out["reciprocity_error"] = reciprocity.mean_error;
    out["reciprocity_error_max"] = reciprocity.max_error;
  }
  out["row_sum"] = row_sum_facts(row_sums);
  if (element_row_sums) out["element_row_sum"] = row_sum_facts(*element_row_sums);
  if (cancel_requested()) {
    out["interrupted"] = true;
    out["completed"] =
        !form_factors_complete ? std::string("form factors not finished")
        : progressive ? fmt::format("{} shots, unshot {:.3g}%", result.steps, 100 * result.unshot_fraction)
                      : fmt::format("{} sweeps", result.steps);
  }
  return out;
}

// Every element's row to the patches, their memory checked first; adds the seconds to `seconds`.
ElementRows element_rows(const RadiositySettings& settings, const RadiositySolveOptions& options,
                         const RadiosityMesh& mesh, const std::string& fewer, double& seconds) {
  const std::size_t elements = mesh.elements.size(), patches = mesh.patches.size();
  check_form_factor_memory(element_rows_bytes(elements, patches), settings,
                           fmt::format("the form factors of {} elements to {} patches", elements, patches),
                           fewer);
  ElementRows rows{std::make_shared<ElementToPatch>(static_cast<Eigen::Index>(elements),
                                                    static_cast<Eigen::Index>(patches)),
                   std::vector<double>(elements)};
  Stopwatch form_factor_time;
  fill_element_form_factor_rows(settings, options.seed, mesh, all_rows(elements), *rows.form_factors,
                                rows.sums, options.cluster, options.quiet);
  seconds += form_factor_time.seconds();
  return rows;
}

// The direct solvers' patch system (Gauss-Seidel, or Gaussian elimination, 000 eq. 6-9): its
// rows, their reciprocity and every patch's B (B = E + first shot where Ctrl-C came first).
struct PatchSolution {
  std::vector<double> sums;  // the patch rows' sums
  Reciprocity reciprocity;
  std::vector<Color> radiosity;
  std::size_t steps = 0;
  bool converged = true;
  double form_factor_seconds = 0;
};

PatchSolution solve_patch_system(const RadiositySettings& settings, const RadiositySolveOptions& options,
                                 const RadiosityMesh& mesh, const GaussSeidelCallback& on_sweep) {
  PatchSolution out;
  const std::size_t patch_count = mesh.patches.size();
  out.sums.resize(patch_count);
  Eigen::MatrixXd patch_rows(static_cast<Eigen::Index>(patch_count), static_cast<Eigen::Index>(patch_count));
  Stopwatch form_factor_time;
  fill_patch_form_factor_rows(settings, options.seed, mesh, patch_rows, out.sums, options.cluster,
                              options.quiet);
  out.form_factor_seconds = form_factor_time.seconds();
  out.reciprocity = measure_reciprocity(mesh.patches, patch_rows);
  if (cancelled_anywhere(options.cluster)) {  // Ctrl-C: not solved, B = E
    for (const RadiositySurface& patch : mesh.patches)
      out.radiosity.push_back(patch.emission + patch.first_shot);
    out.converged = false;
    return out;
  }
  const RadiositySystem patches = mesh.patch_system();
  const FormFactorSource patch_source(std::move(patch_rows));
  RadiositySolution solution;
  if (settings.solver != RadiositySolver::gaussian) {
    solution = solve_gauss_seidel(patches, patch_source, settings.threshold,
                                  static_cast<std::size_t>(settings.max_steps), on_sweep);
  } else {
    try {
      solution = solve_gaussian_elimination(patches, patch_source, form_factor_memory_limit(settings));
    } catch (const SolverMemoryError& e) {  // the solver knows bytes, the settings their place
      throw SolverMemoryError(settings.location, e.message(), e.required_bytes(), e.limit_bytes());
    }
  }
  out.radiosity = solution.radiosity;
  out.steps = solution.iterations;
  out.converged = solution.converged;
  return out;
}

}  // namespace

RadiositySolveResult solve_radiosity(const Scene& scene, const RadiositySettings& settings,
                                     const RadiositySolveOptions& options) {
  if (settings.solver == RadiositySolver::hierarchical)
    return solve_hierarchical_radiosity(scene, settings, options);
  Cluster* cluster = options.cluster;
  RadiositySolveResult result;
  Stopwatch mesh_time;
  RadiosityMeshSettings mesh_settings;
  mesh_settings.segments = settings.segments;
  mesh_settings.patch_size = settings.patch_size;
  mesh_settings.element_size = settings.element_size;
  mesh_settings.split_at_contacts = settings.split_at_contacts;
  const bool progressive = settings.solver == RadiositySolver::progressive;
  // Whether Ctrl-C arrived; with several ranks, whether it reached any (a collective), so that all
  // of them take the same branch.
  const auto stopped = [&] { return cancelled_anywhere(cluster); };
  const std::string fewer =
      "raise radiosity.patch_size or radiosity.element_size (fewer patches and elements)";
  refuse_before_meshing(scene, settings, mesh_settings, fewer);
  result.mesh = build_radiosity_mesh(scene, mesh_settings);
  result.mesh_seconds = mesh_time.seconds();
  Stopwatch first_shot_time;
  shoot_scene_lights(scene, result.mesh, all_rows(result.mesh.elements.size()), options.seed, options.quiet);
  double first_shot_seconds = first_shot_time.seconds();
  Stopwatch solve_time;
  double form_factor_seconds = 0;  // of solve_seconds, the time spent computing form factors
  RadiosityMesh& mesh = result.mesh;
  const std::size_t patch_count = mesh.patches.size();

  // The patch system first (direct solvers), its memory checked before anything is computed.
  if (!progressive) {
    const uint64_t solver_bytes =
        settings.solver == RadiositySolver::gaussian ? gaussian_elimination_memory_bytes(patch_count) : 0;
    check_form_factor_memory(
        static_cast<uint64_t>(patch_count) * patch_count * sizeof(double) + solver_bytes +
            element_rows_bytes(mesh.elements.size(), patch_count),
        settings,
        fmt::format("the full matrix of {} patches ({} elements)", patch_count, mesh.elements.size()),
        "use radiosity.solver \"progressive\", or " + fewer);
  }
  // The element rows (before the patch solve: Gauss-Seidel's sweeps are displayed through them
  // for the convergence log), then solutions and adaptive subdivision (000 §6.7.2) until no
  // neighbours differ by more than the threshold.
  ElementRows rows = element_rows(settings, options, mesh, fewer, form_factor_seconds);
  // Elements whose rows sum to ≈ 0 see nothing: the display leaves them out.
  const auto mark_hidden_elements = [&] {
    result.element_hidden.resize(mesh.elements.size());
    for (std::size_t q = 0; q < mesh.elements.size(); ++q)
      result.element_hidden[q] = rows.sums[q] < kHiddenRowSum;
  };
  // The solution so far handed to options.on_step, every step_every shots or every sweep.
  const bool observed = options.on_step && !(cluster && cluster->distributed());
  const std::size_t step_every = std::max<std::size_t>(options.step_every, 1);
  const auto report_step = [&](std::vector<Color> displayed, std::size_t steps, double unshot_fraction) {
    result.element_radiosity = std::move(displayed);
    mark_hidden_elements();
    result.steps = steps;
    result.unshot_fraction = unshot_fraction;
    options.on_step(result);
  };
  PatchSolution patch;
  if (!progressive) {
    // The convergence log: each Gauss-Seidel sweep's patch radiosities gathered to the elements.
    GaussSeidelCallback on_sweep;
    if (observed)
      on_sweep = [&](std::size_t sweep, double, const std::vector<Color>& radiosity) {
        report_step(gather_element_radiosities(mesh.element_system(),
                                               element_to_patch_source(rows.form_factors), radiosity),
                    sweep, 0);
      };
    patch = solve_patch_system(settings, options, mesh, on_sweep);
    form_factor_seconds += patch.form_factor_seconds;
  }

  // Ctrl-C before every row was computed: the rows not begun are zero.
  const bool form_factors_complete = !stopped();
  std::size_t form_factor_rows = (progressive ? 0 : patch_count) + mesh.elements.size();
  const double min_element_size =
      settings.min_element_size > 0 ? settings.min_element_size : mesh.element_size / 8;
  ProgressReporter progress("radiosity", 1000, "per mille of convergence", options.quiet);
  ElementSolution solution;
  for (;;) {
    if (progressive) {
      const auto observe = [&](const ProgressiveRefinement& refinement, std::size_t steps, double fraction) {
        if (steps % step_every == 0)
          report_step(refinement.display_radiosities(settings.ambient), steps, fraction);
      };
      solution = shoot_progressively(
          mesh, rows, settings, progress, options.checkpointing, cluster,
          observed ? observe : std::function<void(const ProgressiveRefinement&, std::size_t, double)>());
      if (observed && solution.steps % step_every != 0)
        report_step(solution.displayed, solution.steps, solution.unshot_fraction);  // the last shot
    } else {
      solution.radiosity = gather_element_radiosities(
          mesh.element_system(), element_to_patch_source(rows.form_factors), patch.radiosity);
      solution.displayed = solution.radiosity;
      solution.steps = patch.steps;
      solution.converged = patch.converged;
    }
    if (!(settings.subdivision_threshold > 0) || stopped()) break;
    const std::vector<bool> split = elements_to_split(mesh, solution.radiosity, rows.sums,
                                                      settings.subdivision_threshold, min_element_size);
    if (std::find(split.begin(), split.end(), true) == split.end()) break;
    const std::vector<uint32_t> new_rows = split_elements_keeping_rows(scene, settings, split, mesh, rows);
    {
      Stopwatch shot_time;
      shoot_scene_lights(scene, mesh, new_rows, options.seed, true);
      first_shot_seconds += shot_time.seconds();
    }
    {
      Stopwatch form_factor_time;
      fill_element_form_factor_rows(settings, options.seed, mesh, new_rows, *rows.form_factors, rows.sums,
                                    cluster, options.quiet);
      form_factor_seconds += form_factor_time.seconds();
    }
    form_factor_rows += new_rows.size();
    ++result.subdivision_passes;
  }
  progress.finish();

  if (progressive && patch_count <= 2048) {  // P² doubles: 32 MiB at most
    // Reciprocity of the substructured patch form factors F_ij = Σ_{q∈i} A_q F_qj / A_i (000 eq. 6-19).
    patch.reciprocity = measure_reciprocity(
        mesh.patches,
        patch_form_factors_from_elements(mesh.element_system(), element_to_patch_source(rows.form_factors))
            .to_dense());
  }
  result.element_radiosity = std::move(solution.displayed);
  mark_hidden_elements();
  result.steps = solution.steps;
  result.unshot_fraction = solution.unshot_fraction;
  result.converged = solution.converged;
  result.form_factor_rows = form_factor_rows;
  result.form_factors = (progressive ? 0 : patch_count * patch_count) +
                        (form_factor_rows - (progressive ? 0 : patch_count)) * patch_count;
  result.form_factor_bytes = element_rows_bytes(mesh.elements.size(), patch_count);
  result.solve_seconds = solve_time.seconds();
  if (options.facts)
    *options.facts = solve_facts(scene, settings, result, {form_factor_seconds, first_shot_seconds},
                                 patch.reciprocity, progressive ? rows.sums : patch.sums,
                                 progressive ? nullptr : &rows.sums, form_factors_complete);
  return result;
}

}  // namespace candela
