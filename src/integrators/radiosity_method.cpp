#include "integrators/radiosity_method.h"

#include <fmt/format.h>

#include <atomic>
#include <exception>
#include <stdexcept>
#include <string>

#include "distributed/cluster.h"
#include "integrators/distributed_tiles.h"
#include "integrators/probe.h"
#include "integrators/progressive_run.h"
#include "integrators/solution_field.h"
#include "io/byte_stream.h"
#include "radiosity/display.h"
#include "radiosity/radiosity_checkpoint.h"
#include "radiosity/solution_export.h"
#include "radiosity/solve.h"
#include "util/error.h"
#include "util/statistics.h"

namespace candela {
namespace {

// What a solution depends on besides the scene object: its radiosity settings (all but the
// display) and the seed of the ray-cast form factors — the render's (a render with
// another seed than the scene's does not reuse the scene's solution).
std::string solution_key(const Scene& scene, const RadiositySettings& r, uint64_t seed) {
  return fmt::format("{}|{}|{}|{}|{}|{}|{}|{}|{}|{}|{}|{}|{}|{}|{}|{}|{}", scene.unique_id,
                     static_cast<int>(r.solver), static_cast<int>(r.form_factors), r.hemicube_resolution,
                     r.ray_cast_samples, r.patch_size, r.element_size, r.segments, r.threshold, r.max_steps,
                     r.ambient, r.subdivision_threshold, r.min_element_size, r.memory_limit_mib,
                     r.split_at_contacts, r.refinement_tolerance, seed);
}

// What ties a checkpoint to the scene and settings that made it: the caller's fingerprint and
// every setting that shapes the mesh, the form factors or the display — not threshold, max_steps
// or memory_limit_mib, which only say how far to go (a resumed run may go further).
std::string checkpoint_fingerprint(const Scene& scene, const RadiositySettings& r,
                                   const RenderRequest& request) {
  const uint64_t seed = request.seed_for(scene);
  return fmt::format("{}|radiosity {} {} {} {} {} {} {} {} {}", request.fingerprint,
                     static_cast<int>(r.form_factors), r.hemicube_resolution, r.ray_cast_samples,
                     r.patch_size, r.element_size, r.segments, r.ambient, r.split_at_contacts, seed);
}

}  // namespace

StandaloneSolution RadiosityMethod::solve_alone(const Scene& scene, bool quiet) const {
  StandaloneSolution out;
  RadiositySolveOptions options;
  options.seed = scene.render.seed;
  options.quiet = quiet;
  options.facts = &out.facts;
  const RadiositySolveResult result = solve_radiosity(scene, settings_, options);
  // The element mesh as --export-solution's PLY holds it: B at each vertex.
  const SolutionMesh mesh = solution_mesh(result);
  out.add("vertices", mesh.positions);
  out.add("faces", mesh.triangles, true);
  out.add("radiosity", mesh.radiosity);
  // Hierarchical radiosity's links (0 for the other solvers); its memory (nodes and links) in the
  // form factors' column, its form factors the links evaluated.
  const double memory_mib = out.facts.value("memory_mib", result.form_factor_bytes / 1048576.0);
  out.columns = {{"patches", fmt::format("{}", result.mesh.patches.size())},
                 {"elements", fmt::format("{}", result.mesh.elements.size())},
                 {"links", fmt::format("{}", out.facts.value("links", 0))},
                 {"steps", fmt::format("{}", result.steps)},
                 {"unshot", fmt::format("{:.4f}%", 100 * result.unshot_fraction)},
                 {"converged", result.converged ? "yes" : "no"},
                 {"mesh s", fmt::format("{:.3f}", result.mesh_seconds)},
                 {"solve s", fmt::format("{:.3f}", result.solve_seconds)},
                 {"form factors", fmt::format("{}", result.form_factors)},
                 {"FF/s", fmt::format("{:.4g}", out.facts.value("form_factors_per_second", 0.0))},
                 {"FF MiB", fmt::format("{:.1f}", memory_mib)}};
  return out;
}

std::shared_ptr<const RadiosityMethod::Solved> RadiosityMethod::solution_for(const Scene& scene,
                                                                             const RenderRequest& request,
                                                                             bool& reused) const {
  const RadiositySettings& settings = settings_;
  const uint64_t seed = request.seed_for(scene);
  const std::string key = solution_key(scene, settings, seed);
  Cluster* cluster = several_ranks(request);
  std::lock_guard lock(cache_mutex_);
  // A checkpoint to write or resume from asks for this run's own solve, as does a convergence log.
  const bool checkpointing = request.checkpoint || request.resume;
  reused = !checkpointing && !request.on_progress && cached_ && cached_key_ == key;
  if (reused) return cached_;
  auto solved = std::make_shared<Solved>();
  // The run's checkpoints (integrators/progressive_run.h): rank 0 reads the one resumed from and
  // sends it to the others, so that every rank shoots the same way from the same state.
  std::optional<ProgressiveRun> run;
  ProgressiveCheckpointing checkpoints;
  std::optional<RadiosityCheckpoint> resumed;
  if (checkpointing) {
    if (settings.solver != RadiositySolver::progressive || settings.subdivision_threshold > 0)
      throw InputError({scene.source, 0, 0, "radiosity.solver"},
                       "checkpoints are for radiosity.solver \"progressive\" without adaptive subdivision "
                       "(radiosity.subdivision_threshold 0)");
    run.emplace(request, checkpoint_fingerprint(scene, settings, request), RunLimits{});
    resumed = run->resume<RadiosityCheckpoint>(unseal_radiosity_checkpoint, {}, true);
    checkpoints = {&run->checkpoints(), run->fingerprint(), resumed ? &*resumed : nullptr};
  }
  RadiositySolveOptions options;
  options.seed = seed;
  options.quiet = request.quiet || (cluster && !cluster->root());
  options.facts = &solved->facts;
  options.checkpointing = checkpointing ? &checkpoints : nullptr;
  options.cluster = cluster;
  if (request.on_progress) {  // each step's solution displayed as render would
    if (request.progress_every > 0) options.step_every = request.progress_every;
    const bool progressive = settings.solver == RadiositySolver::progressive;
    // progressive by value: it lives in this block, the function beyond it (ASan: use after scope).
    const bool hierarchical = settings.solver == RadiositySolver::hierarchical;
    options.on_step = [&, progressive, hierarchical](const RadiositySolveResult& so_far) {
      // Hierarchical radiosity's steps are Jacobi iterations over its links.
      const char* unit = progressive ? "shots" : hierarchical ? "iterations" : "sweeps";
      request.on_progress({unit, so_far.steps,
                           progressive ? std::optional<double>(so_far.unshot_fraction) : std::nullopt, [&] {
                             const SolutionDisplay display(scene, so_far, settings.display,
                                                           request.antialiasing_for(scene), seed);
                             Film image(request.region.width(), request.region.height());
                             display.draw(request.region.x0, request.region.y0, image);
                             return image;
                           }});
    };
  }
  try {
    solved->result = solve_radiosity(scene, settings, options);
  } catch (const std::invalid_argument& e) {
    if (!resumed) throw;
    throw InputError({request.resume->source, 0, 0, {}}, e.what());
  }
  if (checkpointing) {
    solved->facts["checkpoints_written"] = run->checkpoints().written();
    solved->checkpoint = run->checkpoints().take_final();
    if (resumed) solved->facts["resumed_from_shots"] = resumed->steps;
    return solved;  // not kept: the next render may resume from elsewhere
  }
  if (solved->facts.contains("interrupted")) return solved;  // Ctrl-C: not a solution to keep
  cached_ = solved;
  cached_key_ = key;
  return solved;
}

std::optional<AntialiasingRefusal> RadiosityMethod::antialiasing_refusal(
    const Scene& scene, const AntialiasingSettings& antialiasing) const {
  // The ray-cast displays take any samples; gouraud rasterizes at a grid's.
  if (settings_.display != RadiosityDisplay::gouraud) return std::nullopt;
  std::optional<AntialiasingRefusal> refusal = sample_grid_refusal(antialiasing, scene);
  if (refusal) refusal->reason = "radiosity.display \"gouraud\": " + refusal->reason;
  return refusal;
}

// A scene without a bounded shape is bad input, located at its "shapes" (it exited 1 with "the
// radiosity mesh: the scene has zero size", no location).
void RadiosityMethod::refuse_scene(const Scene& scene) const {
  const Bounds3& bounds = scene.bounds();
  if (bounds.empty() || !(length(bounds.diagonal()) > 0))
    throw InputError(
        {scene.source, 0, 0, "shapes"},
        "radiosity meshes the surfaces within the bounded shapes' box (planes are cut there, and "
        "patch_size defaults to an eighth of its size): this scene has no bounded shape of any "
        "size, only unbounded planes");
}

std::unique_ptr<PointProbe> RadiosityMethod::point_probe(const Scene& scene,
                                                         const ProbeSettings& settings) const {
  return make_field_probe(scene, make_radiosity_field(scene, settings_, settings.quiet, settings.seed),
                          settings);
}

RenderResult RadiosityMethod::render(const Scene& scene, const RenderRequest& request) const {
  // The render's aa settings and seed, which may not be the scene's.
  const AntialiasingSettings& antialiasing = request.antialiasing_for(scene);
  refuse_unsupported_antialiasing(*this, scene, antialiasing);  // before the solve
  RenderResult output(request.region);
  RunStatistics& statistics = output.statistics;
  const RadiositySettings& settings = settings_;
  bool reused = false;
  const std::shared_ptr<const Solved> solved = solution_for(scene, request, reused);
  const RadiositySolveResult& solution = solved->result;
  nlohmann::json facts = solved->facts;
  facts["solution_reused"] = reused;
  if (facts.contains("interrupted")) {  // Ctrl-C: the solution so far is displayed
    statistics.extra["interrupted"] = true;
    statistics.extra["completed"] = facts["completed"];
  }
  // The same solution serves every view: the caller may export it (candela render --export-solution).
  output.solution = std::shared_ptr<const RadiositySolveResult>(solved, &solved->result);
  output.checkpoint = solved->checkpoint;
  const PixelRect region = request.region;
  Stopwatch display_time;
  const SolutionDisplay display(scene, solution, settings.display, antialiasing, request.seed_for(scene));
  std::atomic<uint64_t> samples{0};
  // Every rank holds the same solution.
  draw_across_ranks(
      request.cluster, region,
      [&](const PixelRect& area, Film& target) {
        samples.fetch_add(display.draw(area.x0, area.y0, target), std::memory_order_relaxed);
      },
      output.film, statistics);
  const auto pixel_count = static_cast<uint64_t>(region.width()) * region.height();
  if (display.casts_primary_rays()) {  // rasterized: none
    RayCounts primary;
    primary.primary = samples.load();
    if (Cluster* cluster = several_ranks(request)) sum_across_ranks(*cluster, primary);
    statistics.rays.primary += primary.primary;
  }
  statistics.pixels += pixel_count;
  facts["display"] = kRadiosityDisplayNames.name(settings.display);
  facts["display_seconds"] = display_time.seconds();
  statistics.extra["radiosity"] = std::move(facts);
  return output;
}

}  // namespace candela
