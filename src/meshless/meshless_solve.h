// The meshless solution (SPEC §11; seed 002, after Lehtinen et al. 2008), apart from the method
// that displays it (integrators/meshless_method.h): sites sampled from the camera and by rounds of
// secondary rays (meshless/site_sampling.h), one of three bases over them (meshless/meshless_basis.h),
// effective areas (meshless/effective_area.h), a sparse transfer matrix with visibility
// (meshless/transfer_matrix.h), then per light set-up the direct light η and the iteration
// λ ← η + Rλ.
#pragma once

#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <vector>

#include "meshless/meshless_basis.h"
#include "meshless/meshless_settings.h"
#include "meshless/site_hierarchy.h"
#include "meshless/site_sampling.h"
#include "meshless/transfer_matrix.h"

namespace candela {

class Cluster;
class Scene;
class SurfaceEmitterIndex;

// Divisions of a full turn of the curved shapes the effective areas are integrated over.
constexpr int kEffectiveAreaSegments = 64;

// The most transfer entries S may keep: Eigen's 32-bit index, and render.memory_limit_mib (half
// the machine's memory by default) at 16 bytes an entry while S is built (a row's
// (index, value) pairs, then the compressed copy) — past it the build stops and is refused naming
// meshless.spacing (SPEC §15).
std::size_t transfer_entry_limit(const Scene& scene);

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

// The sites, the basis, the effective areas, the hierarchy and the transfer matrix; seed is the
// render's (RenderRequest::seed_for), which need not be the scene's. cancellable: null once
// Ctrl-C arrives between its phases (sampling, areas, transfer matrix), on every rank of cluster
// alike; quiet: no progress bars (rank 0 alone shows them). Refusals (too many sites or transfer
// entries) are InputErrors at settings.location.
std::shared_ptr<MeshlessGeometry> build_meshless_geometry(const Scene& scene,
                                                          const MeshlessSettings& settings, uint64_t seed,
                                                          bool cancellable = false, bool quiet = true,
                                                          Cluster* cluster = nullptr);
// Called after every iteration of λ with η and λ then (the convergence log).
using MeshlessIterationCallback = std::function<void(std::size_t iteration, const std::vector<Color>& eta,
                                                     const std::vector<Color>& lambda)>;

// Direct light η at every site (its samples jittered by seed) and the solve for λ; quiet: no
// progress bar.
MeshlessLighting light_meshless(const Scene& scene, const MeshlessSettings& settings,
                                const MeshlessGeometry& geometry, uint64_t seed, bool quiet = true,
                                const MeshlessIterationCallback& on_iteration = {});

// What a surface point with this albedo reflects of the emitters directly (η at a site, the hybrid
// display per pixel); rays: cosine-distributed rays weighed against the surfaces' samples (0: the
// samples alone); site: the index that seeds them.
Color site_direct_light(const Scene& scene, const SurfaceEmitterIndex& emitters, uint64_t seed,
                        std::size_t site, int rays, const Vec3& point, const Vec3& normal,
                        const Color& albedo);

// The facts of --stats: the geometry's (sites, hierarchy, transfer matrix, timings) and the
// lighting's (iterations, convergence, lighting_seconds).
nlohmann::json meshless_geometry_facts(const MeshlessSettings& settings, const MeshlessGeometry& geometry);
void add_meshless_lighting_facts(const MeshlessLighting& lighting, nlohmann::json& facts);

}  // namespace candela
