#include "integrators/meshless_method.h"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <cmath>

#include "camera/antialiasing.h"
#include "distributed/cluster.h"
#include "integrators/distributed_tiles.h"
#include "integrators/memory_estimate.h"
#include "integrators/probe.h"
#include "integrators/solution_field.h"
#include "meshless/effective_area.h"
#include "meshless/meshless_basis.h"
#include "meshless/meshless_display.h"
#include "scene/direct_irradiance.h"
#include "scene/scene.h"
#include "scene/surface_emitter_index.h"
#include "util/cancellation.h"

namespace candela {

namespace {

// Seed 002 Figure 4.7: the image with every site the eye can see drawn as a red dot (3 × 3
// pixels, 1 × 1 below 256 pixels wide), as bright as the brightest pixel so that it survives any
// tone mapping.
Film with_sites_drawn(const Scene& scene, const SiteSet& sites, const PixelRect& region, const Film& image) {
  Film result = image;
  const Camera& camera = *scene.camera;
  double brightest = 1;
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x)
      brightest = std::max({brightest, image.at(x, y).r, image.at(x, y).g, image.at(x, y).b});
  const double scene_size = length(scene.bounds().diagonal());
  const double far = 4 * scene_size + 4 * length(camera.eye_position()) + 1;
  const Eigen::Matrix4d clip_from_world = camera.view_projection(far * 1e-7, far);
  const int radius = camera.width() >= 256 ? 1 : 0;
  for (const Site& site : sites.sites) {
    const Eigen::Vector4d clip =
        clip_from_world * Eigen::Vector4d(site.position.x, site.position.y, site.position.z, 1);
    if (!(clip.w() > 0)) continue;
    // The rasterizer's convention: x = (ndc_x + 1)/2·width, y = (1 − ndc_y)/2·height.
    const double px = (clip.x() / clip.w() + 1) / 2 * camera.width(),
                 py = (1 - clip.y() / clip.w()) / 2 * camera.height();
    // Seen when the camera ray through that image point first hits the surface at the site
    // (perspective and orthographic cameras alike).
    const Ray view = camera.generate_ray(px, py);
    const double along = dot(site.position - view.origin, view.direction);
    if (!(along > 0)) continue;
    Intersection hit;
    if (!scene.intersect(view, hit)) continue;
    if (std::fabs(hit.surface.t - along) > 1e-6 * (along + scene_size)) continue;
    const int cx = static_cast<int>(std::floor(px)), cy = static_cast<int>(std::floor(py));
    for (int y = cy - radius; y <= cy + radius; ++y)
      for (int x = cx - radius; x <= cx + radius; ++x)
        if (x >= region.x0 && x < region.x1 && y >= region.y0 && y < region.y1)
          result.at(x - region.x0, y - region.y0) = Color(brightest, 0, 0);
  }
  return result;
}

// What a solution depends on besides the scene object: the meshless settings that shape the
// geometry (not the display, the tolerance or the lights) and the seed — the render's (a
// render with another seed than the scene's does not reuse the scene's sites).
std::string geometry_key(const Scene& scene, const MeshlessSettings& m, uint64_t seed) {
  // The sites are sampled through the camera: another view samples its own.
  const Camera& camera = *scene.camera;
  const Vec3 eye = camera.eye_position(), gaze = camera.view_direction();
  return fmt::format("{}|{}|{}|{}|{}|{}|{}|{}|{}|{}|{}|{}|{}|{}|{}|{}|{},{},{}|{},{},{}|{}x{}",
                     scene.unique_id, static_cast<int>(m.transport), m.cluster_angle,
                     static_cast<int>(m.basis), static_cast<int>(m.kernel), m.spacing, m.neighbours, m.grid,
                     m.rounds, static_cast<int>(m.effective_area), m.shepard_power, m.max_sites,
                     m.gather_rays, m.near_field, seed, static_cast<const void*>(&camera), eye.x, eye.y,
                     eye.z, gaze.x, gaze.y, gaze.z, camera.width(), camera.height());
}

}  // namespace

std::unique_ptr<PointProbe> MeshlessMethod::point_probe(const Scene& scene,
                                                        const ProbeSettings& settings) const {
  return make_field_probe(scene, make_meshless_field(scene, settings_, settings.seed), settings);
}

std::vector<MemoryPart> MeshlessMethod::memory_needed(const Scene& scene,
                                                      const RenderRequest& request) const {
  std::vector<MemoryPart> parts = Method::memory_needed(scene, request);
  // The sites with their radii, areas, coefficients and index: well under a kilobyte each.
  parts.push_back({fmt::format("up to {} sites", settings_.max_sites),
                   static_cast<uint64_t>(settings_.max_sites) * 1024, "meshless.max_sites",
                   "lower it, or raise meshless.spacing"});
  if (settings_.effective_area == MeshlessAreas::integrated) {
    // The surfaces as integrate_effective_areas tessellates them (planes end where sites reach: a
    // few triangles whatever the box).
    const std::size_t triangles = tessellated_triangle_count(
        scene, effective_area_tessellation(scene, site_spacing(scene, settings_.spacing) / 4,
                                           kEffectiveAreaSegments));
    parts.push_back({fmt::format("the effective-area integration's {} triangles", triangles),
                     static_cast<uint64_t>(triangles) * kEffectiveAreaTriangleBytes,
                     "meshless.effective_area",
                     "set it to \"thesis\" (A = πh²/(m + 1), no integration over the tessellated surfaces)"});
  }
  // The transfer matrix's size is known only as it is built: it is refused then, past
  // render.memory_limit_mib at 16 bytes an entry (transfer_entry_limit).
  return parts;
}

namespace {

// A solution without an image (solve_meshless: solve_alone for bench --solve and Python's
// candela.solution; make_meshless_field: probe) is held to render.memory_limit_mib before any work,
// as a render is (Method::memory_needed; the render's own check is its caller's, per view).
void refuse_solution_beyond_memory_limit(const Scene& scene, const MeshlessSettings& settings) {
  refuse_beyond_memory_limit(MeshlessMethod(settings), scene, RenderRequest{});
}

}  // namespace

MeshlessSolution solve_meshless(const Scene& scene, const MeshlessSettings& settings, nlohmann::json* facts) {
  refuse_solution_beyond_memory_limit(scene, settings);
  const std::shared_ptr<MeshlessGeometry> geometry =
      build_meshless_geometry(scene, settings, scene.render.seed);
  MeshlessLighting lighting = light_meshless(scene, settings, *geometry, scene.render.seed);
  if (facts) {
    *facts = meshless_geometry_facts(settings, *geometry);
    add_meshless_lighting_facts(lighting, *facts);
  }
  MeshlessSolution solution;
  solution.sites = geometry->sites;
  solution.matrix = geometry->matrix;
  solution.areas = geometry->areas;
  solution.eta = std::move(lighting.eta);
  solution.transfer = std::move(lighting.transfer);
  return solution;
}

StandaloneSolution MeshlessMethod::solve_alone(const Scene& scene, bool) const {
  StandaloneSolution out;
  const MeshlessSolution solution = solve_meshless(scene, settings_, &out.facts);
  // The sites, and at each the coefficients the display interpolates with the basis: λ (the
  // reflected radiosity, η included), η (its direct part), the effective area and the object.
  std::vector<Vec3> positions, normals;
  for (const Site& site : solution.sites.sites) {
    positions.push_back(site.position);
    normals.push_back(site.normal);
  }
  out.add("positions", positions);
  out.add("normals", normals);
  out.add("radiosity", solution.transfer.lambda);
  out.add("direct", solution.eta);
  out.add("area", solution.areas);
  out.add("object", solution.sites.object, true);
  // Levels 1 and no links for the flat matrix; the hierarchy's levels and cluster links.
  const TransferMatrix& matrix = solution.matrix;
  out.columns = {{"sites", fmt::format("{}", solution.sites.sites.size())},
                 {"levels", fmt::format("{}", out.facts.value("hierarchy_levels", 1))},
                 {"entries", fmt::format("{}", matrix.entries())},
                 {"links", fmt::format("{}", matrix.cluster_links)},
                 {"density", fmt::format("{:.4f}", matrix.density())},
                 {"S MiB", fmt::format("{:.1f}", matrix.bytes() / 1048576.0)},
                 {"sample s", fmt::format("{:.3f}", out.facts.value("sampling_seconds", 0.0))},
                 {"areas s", fmt::format("{:.3f}", out.facts.value("area_seconds", 0.0))},
                 {"S s", fmt::format("{:.3f}", matrix.seconds)},
                 {"iters", fmt::format("{}", solution.transfer.iterations)},
                 {"solve s", fmt::format("{:.3f}", out.facts.value("lighting_seconds", 0.0))}};
  return out;
}

std::shared_ptr<const MeshlessGeometry> MeshlessMethod::geometry_for(const Scene& scene, uint64_t seed,
                                                                     bool& reused, Cluster* cluster,
                                                                     bool quiet) const {
  const std::string key = geometry_key(scene, settings_, seed);
  std::lock_guard lock(cache_mutex_);
  reused = cached_ && cached_key_ == key;
  if (reused) return cached_;
  std::shared_ptr<const MeshlessGeometry> geometry =
      build_meshless_geometry(scene, settings_, seed, true, quiet, cluster);
  if (!geometry) return nullptr;  // Ctrl-C: nothing kept
  cached_ = std::move(geometry);
  cached_key_ = key;
  return cached_;
}

RenderResult MeshlessMethod::render(const Scene& scene, const RenderRequest& request) const {
  RenderResult output(request.region);
  Film& film = output.film;
  RunStatistics& statistics = output.statistics;
  // The sites, areas and transfer matrix are kept between renders of the same scene (other views,
  // other light set-ups: --relight); the direct light and the iteration are redone every time.
  bool reused = false;
  Cluster* cluster = several_ranks(request);
  // The render's seed and aa settings, which may not be the scene's.
  const uint64_t seed = request.seed_for(scene);
  const AntialiasingSettings& antialiasing = request.antialiasing_for(scene);
  const std::shared_ptr<const MeshlessGeometry> geometry =
      geometry_for(scene, seed, reused, cluster, request.quiet);
  // Ctrl-C before λ exists: the film stays black.
  const auto interrupted = [&](const char* completed) {
    statistics.extra["interrupted"] = true;
    statistics.extra["completed"] = completed;
    statistics.extra["meshless"] = {{"interrupted", true}};
    return std::move(output);
  };
  if (!geometry) return interrupted("transfer matrix not finished");
  if (cancelled_anywhere(cluster)) return interrupted("sites and transfer matrix; no lighting");
  const MeshlessSettings& settings = settings_;
  const MeshlessBasis& basis = *geometry->basis;
  // What the display shows: the lighting's η and λ, or an iteration's (the convergence log).
  struct Shown {
    const std::vector<Color>* eta = nullptr;
    const std::vector<Color>* lambda = nullptr;
  } solution;
  const Camera& camera = *scene.camera;
  const PixelRect region = request.region;
  const SurfaceEmitterIndex emitters(scene);
  // The radiance of the display along the camera ray through image point (x, y).
  const RadianceFunction radiance = [&](double x, double y) {
    return meshless_display_radiance(scene, settings, basis, *solution.eta, *solution.lambda, emitters, seed,
                                     camera.generate_ray(x, y));
  };
  // The pixels of area into target (area-sized), through the scene's aa sampling and filter.
  std::atomic<uint64_t> camera_rays{0};
  const auto draw = [&](const PixelRect& area, Film& target) {
    const SamplingRegion at{area.x0, area.y0, camera.width(), camera.height()};
    const SamplingResult sampled =
        sample_image(antialiasing, seed, at, scene.render.tile_size, radiance, target);
    camera_rays.fetch_add(sampled.traced, std::memory_order_relaxed);
  };
  MeshlessIterationCallback on_iteration;
  if (request.on_progress)  // each iteration's λ displayed as render would
    on_iteration = [&](std::size_t iteration, const std::vector<Color>& eta,
                       const std::vector<Color>& lambda) {
      request.on_progress({"iterations", iteration, std::nullopt, [&] {
                             solution = {&eta, &lambda};
                             Film image(region.width(), region.height());
                             draw(region, image);
                             return image;
                           }});
    };
  const MeshlessLighting lighting = light_meshless(
      scene, settings_, *geometry, seed, request.quiet || (cluster && !cluster->root()), on_iteration);
  nlohmann::json facts = meshless_geometry_facts(settings_, *geometry);
  add_meshless_lighting_facts(lighting, facts);
  facts["geometry_reused"] = reused;
  output.relighting = RelightingCost{lighting.seconds, lighting.transfer.iterations};
  solution = {&lighting.eta, &lighting.transfer.lambda};
  camera_rays = 0;  // the final display's alone
  const Stopwatch display_time;
  draw_across_ranks(request.cluster, region, draw, film,
                    statistics);  // every rank holds the same λ
  // Rank 0 holds the whole image, and its result is the one written.
  if (request.sites_image && (!cluster || cluster->root()))
    output.sites_image = with_sites_drawn(scene, geometry->sites, region, film);
  const auto pixel_count = static_cast<uint64_t>(region.width()) * region.height();
  RayCounts primary;
  primary.primary = camera_rays.load();
  if (cluster) sum_across_ranks(*cluster, primary);  // every rank traced its own tiles
  statistics.rays.primary += primary.primary;
  statistics.pixels += pixel_count;
  facts["display_seconds"] = display_time.seconds();
  statistics.extra["meshless"] = std::move(facts);
  if (cancel_requested()) {  // Ctrl-C during the lighting or the display: λ exists and is shown whole
    statistics.extra["interrupted"] = true;
    statistics.extra["completed"] = "sites, transfer matrix and lighting";
  }
  return output;
}

namespace {

// The global display's field: Σ λ_i φ_i at the hit, the normal turned toward the ray's origin.
class MeshlessField final : public SolutionField {
 public:
  MeshlessField(const Scene& scene, std::shared_ptr<const MeshlessGeometry> geometry,
                MeshlessLighting lighting, uint64_t seed)
      : scene_(scene), geometry_(std::move(geometry)), lighting_(std::move(lighting)), seed_(seed) {}
  bool exitance(const Ray& ray, const Intersection& hit, Color& exitance) const override {
    const Site p{hit.surface.position, face_forward(hit.surface.geometric_normal, -ray.direction)};
    thread_local std::vector<std::pair<uint32_t, double>> weights;
    geometry_->basis->evaluate(p, weights);
    if (weights.empty()) return false;
    exitance = scene_.material_of(hit).emission;  // λ holds the reflected light alone
    for (const auto& [i, phi] : weights) exitance += lighting_.transfer.lambda[i] * phi;
    return true;
  }
  // What rays cannot hit: the lights (the same samples and shadows as η).
  Color direct_irradiance(const Vec3& point, const Vec3& normal) const override {
    return candela::direct_irradiance(scene_, point, normal, EmitterSet::lights, StratumJitter{true, seed_});
  }

 private:
  const Scene& scene_;
  std::shared_ptr<const MeshlessGeometry> geometry_;
  MeshlessLighting lighting_;
  uint64_t seed_;
};

}  // namespace

std::unique_ptr<SolutionField> make_meshless_field(const Scene& scene, const MeshlessSettings& settings,
                                                   uint64_t seed) {
  refuse_solution_beyond_memory_limit(scene, settings);
  std::shared_ptr<const MeshlessGeometry> geometry = build_meshless_geometry(scene, settings, seed);
  MeshlessLighting lighting = light_meshless(scene, settings, *geometry, seed);
  return std::make_unique<MeshlessField>(scene, std::move(geometry), std::move(lighting), seed);
}

}  // namespace candela
