// A scene's radiosity solution (SPEC §10; 000 §6), one direction through src/radiosity: the scene
// meshed into patches and elements (radiosity_mesh.h, 000 §6.7.1), the stored form factors' memory
// checked before anything is computed (form_factor_memory.h), the form-factor rows
// (form_factor_rows.h), the solve (solvers.h), and adaptive subdivision (adaptive_subdivision.h,
// 000 §6.7.2) until no neighbours differ too much. By radiosity.solver:
//   progressive   ProgressiveRefinement with the elements receiving (000 §6.6 with
//                 substructuring): the element rows F_qj, computed once, are what every shot
//                 reads; with radiosity.ambient the displayed radiosities add ρ_q·B_amb
//                 (000 §6.6.2), never fed back.
//   gauss-seidel  the patch system (000 eq. 6-9) with form-factor rows over the patches, by
//   gaussian      Gauss-Seidel sweeps or LU elimination, then the elements gathered from the
//                 patch solution, B_q = E_q + ρ_q Σ_j F_qj B_j (000 eq. 6-16).
// The row sums and reciprocity are reported (diagnostics.h). The solution is computed
// sequentially (the form-factor rows in parallel, each row by one thread into its own place), so
// it does not depend on the thread count.
#pragma once

#include <cstdint>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "io/checkpoint_schedule.h"
#include "radiosity/radiosity_checkpoint.h"
#include "radiosity/radiosity_settings.h"
#include "radiosity/radiosity_solve_result.h"

namespace candela {

class Cluster;
class Scene;

// Checkpointing a progressive solution: the state sealed (radiosity_checkpoint.h) and handed to
// the run's schedule between shots and when the shooting ends (converged, out of steps or
// interrupted); and the state it starts from instead of B = E, ΔB = E.
struct ProgressiveCheckpointing {
  CheckpointSchedule* schedule = nullptr;  // never null: when the state is handed out
  std::string fingerprint;
  const RadiosityCheckpoint* resume = nullptr;
};

struct RadiositySolveOptions {
  uint64_t seed = 0;   // the ray-cast form factors' random streams
  bool quiet = false;  // no progress bar
  // Where what the solve measured goes when not null: the "radiosity" facts of render --stats
  // without the display's (steps, form_factors_per_second, row_sum, ...).
  nlohmann::json* facts = nullptr;
  // Progressive without adaptive subdivision only; null: no checkpoints.
  ProgressiveCheckpointing* checkpointing = nullptr;
  // Several ranks: the rows farmed out and Ctrl-C agreed, every rank ending with the
  // one-process solution; null: this process alone.
  Cluster* cluster = nullptr;
  // The convergence log's hook: called with the solution so far — its mesh, element radiosities
  // (as displayed), hidden elements, steps and unshot fraction — after every `step_every` shots
  // (progressive) or every sweep (gauss-seidel), in one process. Empty: none.
  std::function<void(const RadiositySolveResult& so_far)> on_step = {};
  std::size_t step_every = 50;
};

// Meshes and solves the scene. Throws SolverMemoryError for form factors that would not fit,
// std::invalid_argument for a checkpoint that does not fit the mesh (and for bad meshes).
RadiositySolveResult solve_radiosity(const Scene& scene, const RadiositySettings& settings,
                                     const RadiositySolveOptions& options);

}  // namespace candela
