// The `radiosity` method (SPEC §10; 000 §6): classic radiosity on a mesh of patches and elements
// (radiosity/radiosity_mesh.h, 000 §6.7.1), form factors by the hemicube (000 §6.4) or by ray
// casting (setting radiosity.form_factors: "hemicube" or "ray-cast", which multiplies Lambert's
// exact point-to-polygon form factor by the fraction of radiosity.ray_cast_samples² rays through
// the accelerator that reach the target), and a view-independent solution displayed by ray
// casting. Every form factor is taken from a surface's centroid (the seed's point approximation).
//
// Solvers (setting radiosity.solver):
//   progressive   000 §6.6 with substructuring (000 §6.7.1): the patch j with the largest unshot
//                 flux ΔB_j·A_j shoots to the ELEMENTS; every element q receives
//                     ΔRad_q = ρ_q ΔB_j F_qj                 (000 eqs. 6-12, 6-13)
//                 with F_qj from q's centroid to the patches (computed once for
//                 all elements, in parallel: memory elements × patches; each such row sums to 1
//                 in a closed scene, which the shooter's hemicube with reciprocity
//                 F_qj = F_jq A_j / A_q does not give elements near the shooter: a furnace then
//                 shows ±17%). B_q += ΔRad_q; the unshot radiosity of q's patch grows by the
//                 area-weighted mean of its elements' gains. Until the unshot flux is at most
//                 radiosity.threshold of the emitted flux, or radiosity.max_steps shots. With
//                 radiosity.ambient the display adds ρ_q·B_amb (000 §6.6.2), never fed back.
//   gauss-seidel  the patch system (000 eq. 6-9) with form-factor rows over the patches, by
//   gaussian      Gauss-Seidel sweeps or LU elimination, then the elements gathered from the
//                 patch solution, B_q = E_q + ρ_q Σ_j F_qj B_j (000 eq. 6-16), with F_qj from
//                 every element's centroid to the patches.
//
// Display (setting radiosity.display, 000 §6.5):
//   flat     one ray through each pixel centre; its hit → the element of the hit primitive
//            nearest the hit point → that element's radiosity B (the exitance, view
//            independent), shown directly as the seed's radiosity images are.
//   gouraud  (default) the vertex radiosities of radiosity/vertex_radiosity.h; the elements drawn
//            as triangles by the scanline rasterizer in 32 × 32 tiles, colors interpolated
//            perspective-correctly.
// Pixels no surface covers show the background. Each pixel depends only on the solution and its
// own ray or tile, and the solution is computed sequentially (the form-factor rows in parallel,
// each row by one thread into its own place), so the image does not depend on the thread count.
//
// The pipeline lives in src/radiosity, one direction: mesh (radiosity_mesh.h) → form factors
// (form_factor_rows.h) → solve (solve.h, solvers.h; adaptive_subdivision.h, diagnostics.h,
// form_factor_memory.h) → display (display.h). This file adapts it to a Method: it reads the
// settings and the render request (checkpoints, resume, export, ranks) and keeps the solution.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "integrators/method.h"
#include "radiosity/radiosity_settings.h"
#include "radiosity/radiosity_solve_result.h"

namespace candela {

// One solution serves every view: render() keeps the last scene's solution (recognised by
// Scene::unique_id and the radiosity settings and the render's seed, RenderRequest::seed_for) and reuses it
// when called again for the same scene with another camera.
class RadiosityMethod final : public Method {
 public:
  explicit RadiosityMethod(const RadiositySettings& settings = {}) : settings_(settings) {}
  std::string_view name() const override { return "radiosity"; }
  RenderResult render(const Scene& scene, const RenderRequest& request) const override;
  // Every aa mode and filter; gouraud, which rasterizes (the jittered modes in passes,
  // camera/accumulation_buffer.h), refuses a grid too large to hold (camera/sample_grid.h).
  std::optional<AntialiasingRefusal> antialiasing_refusal(
      const Scene& scene, const AntialiasingSettings& antialiasing) const override;
  bool rasterizes() const override { return settings_.display == RadiosityDisplay::gouraud; }
  // A scene with no bounded shape of any size (only planes): nothing to mesh within.
  void refuse_scene(const Scene& scene) const override;
  // The ray-traced display's field, solved now, gathered over the hemisphere (integrators/probe.h).
  std::unique_ptr<PointProbe> point_probe(const Scene& scene, const ProbeSettings& settings) const override;
  // The element mesh (vertices, faces, each vertex's radiosity B) and the solve's facts.
  StandaloneSolution solve_alone(const Scene& scene, bool quiet) const override;

 private:
  struct Solved {
    RadiositySolveResult result;
    nlohmann::json facts;             // what the solve measured, for --stats
    std::optional<Bytes> checkpoint;  // the final state, with RenderRequest::checkpoint
  };
  // The cached solution when the scene and its settings are the ones last solved (reused set),
  // else a new one, which replaces it.
  // With a checkpoint to hand out or resume from (request.checkpoint / resume: progressive solver
  // only) the solve is this run's own and not kept.
  std::shared_ptr<const Solved> solution_for(const Scene& scene, const RenderRequest& request,
                                             bool& reused) const;

  RadiositySettings settings_;
  mutable std::mutex cache_mutex_;
  mutable std::shared_ptr<const Solved> cached_;
  mutable std::string cached_key_;  // Scene::unique_id and the settings the solution used
};

}  // namespace candela
