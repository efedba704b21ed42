#include "meshless/meshless_solve.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "distributed/cluster.h"
#include "meshless/effective_area.h"
#include "scene/direct_irradiance.h"
#include "scene/light.h"
#include "scene/scene.h"
#include "scene/surface_emitter_index.h"
#include "util/cancellation.h"
#include "util/memory.h"
#include "util/progress.h"
#include "util/statistics.h"

namespace candela {
namespace {

// The number of sites on each level of the hierarchy, finest first (one level without one).
std::vector<std::size_t> level_sizes(const MeshlessGeometry& geometry) {
  if (!geometry.hierarchy) return {geometry.sites.sites.size()};
  std::vector<std::size_t> sizes;
  for (std::size_t l = 0; l < geometry.hierarchy->level_count(); ++l)
    sizes.push_back(geometry.hierarchy->level_sites(l).size());
  return sizes;
}

}  // namespace

// What a surface point reflects of the emitters directly: ρ Σ I·max(0, n·L)·V over every sample of
// the lights, the emissive surfaces and the environment (opaque shadows), the samples of each
// jittered in their cells as the local model's are. An emissive surface lights the
// sites through these shadow rays, not through the sites that land on it, so a lamp's power no
// longer depends on them; its own emission is drawn where the camera sees it, never transferred.
// Also through `rays` cosine-distributed rays from the site, weighed against the
// surfaces' samples (scene/direct_irradiance.h) — a site beside a glowing wall got 0.25–27 times
// its irradiance from the samples alone, 2 % low on average in a glowing box.
Color site_direct_light(const Scene& scene, const SurfaceEmitterIndex& emitters, uint64_t seed,
                        std::size_t site, int rays, const Vec3& point, const Vec3& normal,
                        const Color& albedo) {
  if (albedo.is_black()) return Color();
  const StratumJitter jitter{true, seed};
  Pcg32 random(seed ^ 0x6D6573686C657373ull, site);
  const HemisphereRays hemisphere{emitters, rays, random};
  return albedo * direct_irradiance(scene, point, normal, EmitterSet::everything, jitter, &hemisphere);
}

// The most transfer entries S may keep: Eigen's 32-bit index, and render.memory_limit_mib (half
// the machine's memory by default) at 16 bytes an entry while S is built (a row's
// (index, value) pairs, then the compressed copy) — past it the build stops and is refused naming
// meshless.spacing (SPEC §15).
std::size_t transfer_entry_limit(const Scene& scene) {
  const std::size_t index_limit = std::size_t{INT32_MAX} - 1;
  return std::min<std::size_t>(
      index_limit, static_cast<std::size_t>(memory_limit_bytes(scene.render.memory_limit_mib) / 16));
}

std::shared_ptr<MeshlessGeometry> build_meshless_geometry(const Scene& scene,
                                                          const MeshlessSettings& settings, uint64_t seed,
                                                          bool cancellable, bool quiet, Cluster* cluster) {
  // Every rank stops at the same phase (a collective when distributed).
  const auto stop = [&] { return cancellable && cancelled_anywhere(cluster); };
  auto geometry = std::make_shared<MeshlessGeometry>();
  Stopwatch phase;
  SiteSamplingSettings sampling;
  sampling.grid = settings.grid;
  sampling.rounds = settings.rounds;
  sampling.spacing = settings.spacing;
  sampling.neighbours = settings.neighbours;
  sampling.seed = seed;
  sampling.max_sites = static_cast<std::size_t>(settings.max_sites);
  {
    ProgressReporter progress("sites", 1 + static_cast<uint64_t>(settings.rounds), "rounds",
                              quiet || (cluster && !cluster->root()));
    try {
      geometry->sites = sample_sites(scene, sampling, &progress);
    } catch (const std::invalid_argument& e) {  // too many sites for the settings: bad input
      throw InputError(settings.location, e.what());
    }
    progress.finish();
  }
  geometry->sampling_seconds = phase.seconds();
  if (stop()) return nullptr;
  const SiteSet& sites = geometry->sites;

  phase = Stopwatch();
  // The basis refers to the geometry's own sites and radii, which stay where they are: the
  // geometry is held by a pointer and never moved.
  geometry->basis = std::make_unique<MeshlessBasis>(sites.sites, sites.radius, settings.basis,
                                                    settings.kernel, settings.shepard_power);
  geometry->areas = sites.effective_area;  // the thesis's πh²/(m + 1)
  if (settings.effective_area == MeshlessAreas::integrated)
    geometry->areas = integrate_effective_areas(scene, *geometry->basis, sites, sites.spacing / 4,
                                                kEffectiveAreaSegments, cluster, quiet);
  geometry->area_seconds = phase.seconds();
  if (stop()) return nullptr;
  // The longest phase shows its rows (rank 0, for every rank).
  ProgressReporter progress("transfer matrix", sites.sites.size(), "sites",
                            quiet || (cluster && !cluster->root()));
  TransferSettings transfer;
  transfer.gather_rays = settings.gather_rays;
  transfer.near_field = settings.near_field;
  transfer.seed = seed;
  transfer.max_entries = transfer_entry_limit(scene);
  transfer.cluster_angle = settings.cluster_angle;
  if (settings.transport == MeshlessTransport::hierarchical) {
    phase = Stopwatch();
    try {
      geometry->hierarchy = std::make_unique<SiteHierarchy>(sites, settings.neighbours);
    } catch (const std::invalid_argument& e) {  // settings the sites cannot be thinned with: bad input
      throw InputError(settings.location, e.what());
    }
    geometry->hierarchy_seconds = phase.seconds();
  }
  try {
    geometry->matrix = compute_transfer_matrix(scene, sites, *geometry->basis, geometry->areas, transfer,
                                               cluster, &progress, geometry->hierarchy.get());
  } catch (const std::invalid_argument& e) {  // more entries than memory holds: bad input
    throw InputError(settings.location, e.what());
  }
  progress.finish();
  return geometry;
}

MeshlessLighting light_meshless(const Scene& scene, const MeshlessSettings& settings,
                                const MeshlessGeometry& geometry, uint64_t seed, bool quiet,
                                const MeshlessIterationCallback& on_iteration) {
  const SiteSet& sites = geometry.sites;
  const Stopwatch phase;
  MeshlessLighting lighting;
  lighting.eta.resize(sites.sites.size());
  const SurfaceEmitterIndex emitters(scene);
  // Albedo edits (R = QS): Q as the scene's materials have it now — a relight frame may
  // give a material another kd; a constant kd is read afresh, a textured one is as it was where
  // the site was sampled. S does not depend on it.
  std::vector<Color> albedo = sites.albedo;
  tbb::parallel_for(std::size_t(0), sites.sites.size(), [&](std::size_t i) {
    const Material& material = scene.materials[scene.primitives[sites.primitive[i]].material];
    if (material.kd && material.kd->is_constant()) {
      SurfaceProperties properties;
      properties.kd = material.kd->evaluate(SurfaceHit{});
      albedo[i] = properties.diffuse_albedo();
    }
    lighting.eta[i] = site_direct_light(scene, emitters, seed, i, settings.gather_rays,
                                        sites.sites[i].position, sites.sites[i].normal, albedo[i]);
  });
  ProgressReporter progress("meshless solve", 1000, "per mille of convergence", quiet);
  TransferIterationCallback each_iteration;
  if (on_iteration)
    each_iteration = [&](std::size_t iteration, const std::vector<Color>& lambda) {
      on_iteration(iteration, lighting.eta, lambda);
    };
  lighting.transfer =
      solve_transfer(geometry.matrix, albedo, lighting.eta, settings.tolerance,
                     static_cast<std::size_t>(settings.max_iterations), &progress, each_iteration);
  progress.finish();
  lighting.seconds = phase.seconds();
  return lighting;
}

nlohmann::json meshless_geometry_facts(const MeshlessSettings& settings, const MeshlessGeometry& geometry) {
  double area_sum = 0;
  for (const double a : geometry.areas) area_sum += a;
  return {{"basis", kBasisNames.name(settings.basis)},
          {"sites", geometry.sites.sites.size()},
          {"camera_sites", geometry.sites.camera_sites},
          {"spacing", geometry.sites.spacing},
          {"neighbours", settings.neighbours},
          {"effective_area", kMeshlessAreaNames.name(settings.effective_area)},
          {"effective_area_sum", area_sum},
          {"transport", kMeshlessTransportNames.name(settings.transport)},
          {"hierarchy_levels", geometry.hierarchy ? geometry.hierarchy->level_count() : 1},
          {"hierarchy_nodes",
           geometry.hierarchy ? geometry.hierarchy->node_count() : geometry.sites.sites.size()},
          {"hierarchy_level_sites", level_sizes(geometry)},
          {"hierarchy_seconds", geometry.hierarchy_seconds},
          {"cluster_links", geometry.matrix.cluster_links},
          {"transfer_entries", geometry.matrix.entries()},
          {"transfer_density", geometry.matrix.density()},
          {"transfer_memory_mib", static_cast<double>(geometry.matrix.bytes()) / 1048576.0},
          {"transfer_seconds", geometry.matrix.seconds},
          {"visibility_rays", geometry.matrix.visibility_rays},
          {"gather_rays", geometry.matrix.gather_rays},
          {"far_field_scale", geometry.matrix.far_field_scale},
          {"sampling_seconds", geometry.sampling_seconds},
          {"area_seconds", geometry.area_seconds}};
}

void add_meshless_lighting_facts(const MeshlessLighting& lighting, nlohmann::json& facts) {
  facts["iterations"] = lighting.transfer.iterations;
  facts["converged"] = lighting.transfer.converged;
  facts["diverged"] = lighting.transfer.diverged;
  facts["final_change"] = lighting.transfer.final_change;
  facts["lighting_seconds"] = lighting.seconds;  // direct light and the iteration: a relit frame's cost
}

}  // namespace candela
