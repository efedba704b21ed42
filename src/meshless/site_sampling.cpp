#include "meshless/site_sampling.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>

#include "math/constants.h"
#include "math/pcg32.h"
#include "meshless/site_index.h"
#include "meshless/spacing_filter.h"
#include "scene/scene.h"
#include "util/progress.h"

namespace candela {

namespace {

// A site found by a ray, with what its surface is made of there.
struct FoundSite {
  Site site;
  uint32_t primitive = 0, object = 0;
  int8_t side = 1;
  Color albedo, emission;
};

// The site where a ray first hits the scene, its normal turned toward the ray's origin. Window panes
// are looked through: they reflect nothing diffusely, and the room behind one needs the sites.
std::optional<FoundSite> site_along(const Scene& scene, const Ray& ray) {
  Intersection hit;
  Color through;
  if (!scene.intersect_past_sheets(ray, hit, through)) return std::nullopt;
  FoundSite found;
  found.site = {hit.surface.position, face_forward(hit.surface.geometric_normal, -ray.direction)};
  found.primitive = hit.primitive;
  found.object = scene.primitives[hit.primitive].object;
  found.side = dot(found.site.normal, hit.surface.geometric_normal) > 0 ? int8_t{1} : int8_t{-1};
  const Material& material = scene.material_of(hit);
  const SurfaceProperties properties = material.at(hit.surface);
  found.albedo = properties.diffuse_albedo();
  found.emission = material.emission;
  return found;
}

// A cosine-distributed direction about n (Malley's method).
Vec3 cosine_direction(const Vec3& n, Pcg32& random) {
  const double u = random.next_double(), v = random.next_double();
  const double r = std::sqrt(u), phi = 2 * kPi * v;
  Vec3 b1, b2;
  orthonormal_basis(n, b1, b2);
  return normalize(b1 * (r * std::cos(phi)) + b2 * (r * std::sin(phi)) + n * std::sqrt(std::max(0.0, 1 - u)));
}

}  // namespace

std::vector<uint8_t> sides_with_sites(const SiteSet& set, std::size_t object_count) {
  std::vector<uint8_t> sides(object_count, 0);
  for (std::size_t i = 0; i < set.sites.size() && i < set.object.size() && i < set.side.size(); ++i)
    if (set.object[i] < object_count) sides[set.object[i]] |= set.side[i] > 0 ? 1 : 2;
  return sides;
}

void assign_radii(SiteSet& set, int neighbours) {
  if (neighbours < 1) throw std::invalid_argument("site radii: neighbours must be >= 1");
  const SiteIndex index(set.sites);
  set.radius.assign(set.sites.size(), 0.0);
  set.effective_area.assign(set.sites.size(), 0.0);
  tbb::parallel_for(std::size_t(0), set.sites.size(), [&](std::size_t i) {
    // 002 §4.2.7 and eq. 5.5: h_i, the site distance holding the m nearest other sites.
    const double h = index.mth_nearest_site_distance(set.sites[i], static_cast<std::size_t>(neighbours),
                                                     static_cast<uint32_t>(i));
    set.radius[i] = h;
    set.effective_area[i] = std::isfinite(h) ? kPi * h * h / (neighbours + 1) : 0.0;
  });
}

double site_spacing(const Scene& scene, double spacing) {
  if (spacing > 0) return spacing;
  const Bounds3 bounds = scene.bounds();
  return (bounds.empty() || !bounds.is_finite() ? 1.0 : std::max(length(bounds.diagonal()), 1e-300)) / 50;
}

SiteSet sample_sites(const Scene& scene, const SiteSamplingSettings& settings, ProgressReporter* progress) {
  if (settings.grid < 1) throw std::invalid_argument("site sampling: grid must be >= 1");
  if (settings.rounds < 0) throw std::invalid_argument("site sampling: rounds must be >= 0");
  if (!(settings.spacing >= 0) || !std::isfinite(settings.spacing))
    throw std::invalid_argument("site sampling: spacing must be finite and >= 0");
  if (settings.neighbours < 1) throw std::invalid_argument("site sampling: neighbours must be >= 1");
  SiteSet set;
  const Bounds3 bounds = scene.bounds();
  const double scene_size =
      bounds.empty() || !bounds.is_finite() ? 1.0 : std::max(length(bounds.diagonal()), 1e-300);
  set.spacing = site_spacing(scene, settings.spacing);
  if (set.spacing < 1e-7 * scene_size)
    throw std::invalid_argument(
        fmt::format("site sampling: the spacing {:g} is below 1e-7 of the scene's size {:g}; "
                    "raise meshless.spacing",
                    set.spacing, scene_size));
  SpacingFilter filter(set.spacing);
  const auto offer = [&](const std::optional<FoundSite>& candidate) {
    if (!candidate || !filter.try_keep(candidate->site)) return;
    if (set.sites.size() >= settings.max_sites)
      throw std::invalid_argument("site sampling: more than " + std::to_string(settings.max_sites) +
                                  " sites; raise the spacing Δ");
    set.sites.push_back(candidate->site);
    set.primitive.push_back(candidate->primitive);
    set.albedo.push_back(candidate->albedo);
    set.emission.push_back(candidate->emission);
    set.object.push_back(candidate->object);
    set.side.push_back(candidate->side);
  };

  // 1. Camera rays through a regular grid over the image.
  const Camera& camera = *scene.camera;
  const int grid = settings.grid;
  std::vector<std::optional<FoundSite>> found(static_cast<std::size_t>(grid) * grid);
  tbb::parallel_for(0, grid * grid, [&](int k) {
    const double x = (k % grid + 0.5) * camera.width() / grid, y = (k / grid + 0.5) * camera.height() / grid;
    found[static_cast<std::size_t>(k)] = site_along(scene, camera.generate_ray(x, y));
  });
  for (const auto& candidate : found) offer(candidate);
  set.camera_sites = set.sites.size();
  const auto advance = [&] {
    if (!progress) return;
    progress->set_detail(fmt::format("{} sites", set.sites.size()));
    progress->advance();
  };
  advance();

  // 2–3. Rounds of secondary rays about the normals, pruned as they are added.
  for (int round = 0; round < settings.rounds; ++round) {
    const std::size_t shooters = set.sites.size();
    found.assign(shooters, std::nullopt);
    tbb::parallel_for(std::size_t(0), shooters, [&](std::size_t i) {
      Pcg32 random(settings.seed + 0x9E3779B97F4A7C15ull * static_cast<uint64_t>(round + 1), i);
      const Site& site = set.sites[i];
      Ray ray;
      ray.direction = cosine_direction(site.normal, random);
      ray.origin = site.position + site.normal * scene.ray_offset(site.position);
      found[i] = site_along(scene, ray);
    });
    for (const auto& candidate : found) offer(candidate);
    advance();
  }
  assign_radii(set, settings.neighbours);
  return set;
}

}  // namespace candela
