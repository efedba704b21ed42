// The `meshless` method (SPEC §11; seed 002, after Lehtinen et al. 2008): global illumination of
// diffuse surfaces with finite elements defined by points — sites sampled from the camera and by
// rounds of secondary rays (meshless/site_sampling.h), one of three bases over them
// (meshless/meshless_basis.h), a sparse transfer matrix with visibility and effective areas
// (meshless/transfer_matrix.h, meshless/effective_area.h), and the iteration λ ← η + Rλ.
//
// Units: like the radiosity method, radiosity (exitance) B; radiance is B/π. η_i is what site i
// emits (the material's `emission`) plus what it reflects of the lights directly,
// ρ_i Σ_lights I·max(0, n·L)·V, I the light's intensity with its attenuation (the numbers the local
// model's diffuse term uses); ambient light is not a light here.
//
// Display (meshless.display), at the first hit of one ray through each pixel centre, with the site
// p = (hit, the surface normal turned toward the eye):
//   global    Σ λ_i φ_i(p)
//   direct    Σ η_i φ_i(p)                       (the thesis's direct-light figures)
//   indirect  Σ (λ_i − η_i) φ_i(p)
//   hybrid    the direct term traced exactly at the hit (shadow rays per pixel) plus the indirect
//             interpolation — the thesis's proposed future work.
// Pixels that hit nothing, or where no element reaches, show the background.
#pragma once

#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <string>

#include "integrators/method.h"
#include "io/json_node.h"
#include "meshless/meshless_basis.h"
#include "meshless/site_hierarchy.h"
#include "meshless/site_sampling.h"
#include "meshless/transfer_matrix.h"
#include "util/error.h"

namespace candela {

// How the solution is shown (see above).
enum class MeshlessDisplay { global, direct, indirect, hybrid };
inline constexpr auto kMeshlessDisplayNames =
    enum_names<MeshlessDisplay>({{MeshlessDisplay::global, "global"},
                                 {MeshlessDisplay::direct, "direct"},
                                 {MeshlessDisplay::indirect, "indirect"},
                                 {MeshlessDisplay::hybrid, "hybrid"}});
// The sites' effective areas: integrated over the surfaces (meshless/effective_area.h), or the
// thesis's πh²/(m + 1).
enum class MeshlessAreas { integrated, thesis };
inline constexpr auto kMeshlessAreaNames =
    enum_names<MeshlessAreas>({{MeshlessAreas::integrated, "integrated"}, {MeshlessAreas::thesis, "thesis"}});

// The transfer: the thesis's flat matrix, every far element on its own (n² entries at worst), or
// the hierarchical transport of Lehtinen et al. 2008 (links between nodes of the site
// hierarchy, O(n log n) entries at worst; meshless/site_hierarchy.h, meshless/transfer_matrix.h).
enum class MeshlessTransport { flat, hierarchical };
inline constexpr auto kMeshlessTransportNames = enum_names<MeshlessTransport>(
    {{MeshlessTransport::flat, "flat"}, {MeshlessTransport::hierarchical, "hierarchical"}});

// The scene file's "meshless" object (SPEC §11, seed 002).
struct MeshlessSettings {
  BasisKind basis = BasisKind::normalized;
  RadialKernel kernel = RadialKernel::gaussian;  // the radial basis's mother function
  double spacing = 0;   // Δ: no two sites closer (site distance); 0: the scene's size / 50
  int neighbours = 10;  // m: the radius holds the m nearest sites
  int grid = 64;        // camera rays per image side for the first sites
  int rounds = 4;       // rounds of secondary rays
  MeshlessAreas effective_area = MeshlessAreas::integrated;
  double tolerance = 1e-4;  // the iteration stops when no coefficient changes by more (relative)
  int max_iterations = 1000;
  MeshlessDisplay display = MeshlessDisplay::global;
  double shepard_power = 2;
  int max_sites = 50000;  // refused beyond: the transfer matrix grows as n²
  int gather_rays = 256;  // per site, for the transfer matrix's near field (meshless/transfer_matrix.h)
  double near_field = 2;  // the near field: elements closer than this many of their radii
  MeshlessTransport transport = MeshlessTransport::flat;
  double cluster_angle = 0.15;  // hierarchical: two nodes are linked while extent/distance < this
  // Where a refusal of the sites or the transfer matrix (too many, too much memory)
  // points — the spacing when the scene gives it, else the "meshless" object.
  SourceLocation location;
};
// Ranges checked, unknown keys refused.
MeshlessSettings read_meshless_settings(const JsonNode& node);

// What does not depend on the lights: the sites, the basis over them, the effective areas and
// the transfer matrix S (002 §5.3: relighting reuses them).
struct MeshlessGeometry {
  SiteSet sites;
  std::unique_ptr<MeshlessBasis> basis;      // over sites.sites and sites.radius
  std::vector<double> areas;                 // A_k
  std::unique_ptr<SiteHierarchy> hierarchy;  // hierarchical transport: over sites
  TransferMatrix matrix;                     // S
  double sampling_seconds = 0, area_seconds = 0, hierarchy_seconds = 0;
};

// What the lights give: η (emitted and directly reflected) and λ.
struct MeshlessLighting {
  std::vector<Color> eta;
  TransferSolution transfer;
  double seconds = 0;  // direct light and iteration
};

// seed is the render's (RenderRequest::seed_for), which need not be the scene's.
std::shared_ptr<MeshlessGeometry> build_meshless_geometry(const Scene& scene,
                                                          const MeshlessSettings& settings, uint64_t seed);
// Called after every iteration of λ with η and λ then (the convergence log).
using MeshlessIterationCallback = std::function<void(std::size_t iteration, const std::vector<Color>& eta,
                                                     const std::vector<Color>& lambda)>;

// Direct light η at every site (its samples jittered by seed) and the solve for λ; quiet: no
// progress bar.
MeshlessLighting light_meshless(const Scene& scene, const MeshlessSettings& settings,
                                const MeshlessGeometry& geometry, uint64_t seed, bool quiet = true,
                                const MeshlessIterationCallback& on_iteration = {});

struct MeshlessSolution {
  SiteSet sites;
  std::vector<Color> eta;     // η: emitted and directly reflected
  TransferSolution transfer;  // λ
  TransferMatrix matrix;      // S
  std::vector<double> areas;  // A_k, the effective areas
};

// Samples, builds and solves with the scene's render.seed; fills facts for --stats when given.
// Throws InputError before any work past render.memory_limit_mib.
MeshlessSolution solve_meshless(const Scene& scene, const MeshlessSettings& settings,
                                nlohmann::json* facts = nullptr);

// Keeps the last scene's geometry (recognised by Scene::unique_id, the settings that shape it and
// the render's seed) and reuses it when called again for the same scene: other views, or other
// lights (candela render --relight, which swaps the scene's lights between renders).
class MeshlessMethod final : public Method {
 public:
  explicit MeshlessMethod(const MeshlessSettings& settings = {}) : settings_(settings) {}
  std::string_view name() const override { return "meshless"; }
  RenderResult render(const Scene& scene, const RenderRequest& request) const override;
  // The image, the sites and, with integrated effective areas, the tessellated surfaces.
  std::vector<MemoryPart> memory_needed(const Scene& scene, const RenderRequest& request) const override;

 private:
  std::shared_ptr<const MeshlessGeometry> geometry_for(const Scene& scene, uint64_t seed, bool& reused,
                                                       Cluster* cluster, bool quiet) const;
  MeshlessSettings settings_;
  mutable std::mutex cache_mutex_;
  mutable std::shared_ptr<const MeshlessGeometry> cached_;
  mutable std::string cached_key_;
};

}  // namespace candela
