#include "meshless/effective_area.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "distributed/task_farm.h"
#include "raster/tessellated_scene.h"
#include "scene/scene.h"
#include "util/progress.h"

namespace candela {

TessellationRequest effective_area_tessellation(const Scene& scene, double cell, int segments) {
  TessellationRequest request;
  request.max_segments = segments;
  request.chord_tolerance = cell / 2;
  request.clip = scene.bounds();
  return request;
}

std::vector<double> integrate_effective_areas(const Scene& scene, const MeshlessBasis& basis,
                                              const SiteSet& sites, double cell, int segments,
                                              Cluster* cluster, bool quiet) {
  const std::size_t site_count = sites.sites.size();
  const std::vector<uint8_t> object_sides = sides_with_sites(sites, scene.objects.size());
  if (!(cell > 0) || !std::isfinite(cell))
    throw std::invalid_argument("effective areas: the cell size must be > 0");
  if (segments < 3) throw std::invalid_argument("effective areas: segments must be >= 3");
  // Planes are cut where the elements can reach: around the scene's finite shapes and every site
  // grown by the largest finite radius (a floor plane under a small object holds sites far
  // beyond the object's box).
  TessellationRequest request = effective_area_tessellation(scene, cell, segments);
  double reach = 0;
  for (const double r : sites.radius)
    if (std::isfinite(r)) reach = std::max(reach, r);
  for (const Site& site : sites.sites) {
    request.clip.extend(site.position - Vec3(reach, reach, reach));
    request.clip.extend(site.position + Vec3(reach, reach, reach));
  }
  const TessellatedScene triangles = tessellate_scene(scene, request);
  // At most about kMaxSamples midpoints: a spacing small for the scene widens the cells rather
  // than taking hours and gigabytes (each sub-triangle has about cell²/2 of area).
  constexpr double kMaxSamples = 4e6;
  double surface = 0;
  for (std::size_t t = 0; t < triangles.triangle_count(); ++t)
    surface += 0.5 * length(cross(triangles.corner_positions[3 * t + 1] - triangles.corner_positions[3 * t],
                                  triangles.corner_positions[3 * t + 2] - triangles.corner_positions[3 * t]));
  cell = std::max(cell, std::sqrt(2 * surface / kMaxSamples));
  // Per triangle in parallel, each thread summing into its own vector; the per-triangle sums are
  // added in triangle order afterwards, so the result does not depend on the thread count.
  std::vector<std::vector<std::pair<uint32_t, double>>> contributions(triangles.triangle_count());
  // Seconds on a large scene; rank 0 counts every rank's triangles.
  ProgressReporter progress("effective areas", triangles.triangle_count(), "triangles",
                            quiet || (cluster && !cluster->root()));
  const auto integrate_triangle = [&](std::size_t t) {
    const Vec3 a = triangles.corner_positions[3 * t], b = triangles.corner_positions[3 * t + 1],
               c = triangles.corner_positions[3 * t + 2];
    const Vec3 face = cross(b - a, c - a);
    const double area = 0.5 * length(face);
    if (!(area > 0)) return;
    const Vec3 normal = face / (2 * area);
    const uint8_t sides = triangles.objects[t] < object_sides.size() ? object_sides[triangles.objects[t]] : 0;
    if (sides == 0) return;
    // n × n similar sub-triangles (n² of them: n(n+1)/2 upright, n(n−1)/2 inverted), area/n² each.
    const double longest = std::max({length(b - a), length(c - b), length(a - c)});
    const int n = static_cast<int>(std::clamp(std::ceil(longest / cell), 1.0, 1e5));
    const double weight = area / (static_cast<double>(n) * n);
    const Vec3 du = (b - a) / n, dv = (c - a) / n;
    // Rows of sub-triangles in parallel too (a room's walls are a few large triangles), each row
    // into its own list, joined in order.
    std::vector<std::vector<std::pair<uint32_t, double>>> rows(static_cast<std::size_t>(n));
    tbb::parallel_for(0, n, [&](int i) {
      std::vector<std::pair<uint32_t, double>>& sums = rows[static_cast<std::size_t>(i)];
      std::vector<std::pair<uint32_t, double>> weights;
      const auto sample = [&](const Vec3& point) {
        for (const int side : {1, 2}) {
          if (!(sides & side)) continue;
          basis.evaluate({point, side == 1 ? normal : -normal}, weights);
          double total = 0;
          for (const auto& entry : weights) total += entry.second;
          if (!(total > 0)) continue;
          for (const auto& [k, phi] : weights) sums.emplace_back(k, phi / total * weight);
        }
      };
      for (int j = 0; i + j < n; ++j) {
        const Vec3 corner = a + du * i + dv * j;
        sample(corner + (du + dv) / 3.0);                               // upright
        if (i + j + 1 < n) sample(corner + du + dv - (du + dv) / 3.0);  // inverted
      }
    });
    // One sum per site for the triangle, each site's values added in row order and within a row in
    // the order of its midpoints (thread-independent). A large triangle (a room's wall: millions of
    // values) adds them into one slot per site as they come; a small one sorts its few by site
    // (stable: the same order of addition, the same sums to the bit).
    std::size_t values = 0;
    for (const auto& row : rows) values += row.size();
    std::vector<std::pair<uint32_t, double>> merged;
    if (values > site_count / 4 + 1024) {
      std::vector<double> total(site_count, 0.0);
      std::vector<uint8_t> touched(site_count, 0);
      std::vector<uint32_t> sites_touched;
      for (const auto& row : rows)
        for (const auto& [k, value] : row) {
          if (!touched[k]) touched[k] = 1, sites_touched.push_back(k);
          total[k] += value;
        }
      std::sort(sites_touched.begin(), sites_touched.end());
      for (const uint32_t k : sites_touched) merged.emplace_back(k, total[k]);
    } else {
      std::vector<std::pair<uint32_t, double>> sums;
      for (auto& row : rows) sums.insert(sums.end(), row.begin(), row.end());
      std::stable_sort(sums.begin(), sums.end(),
                       [](const auto& x, const auto& y) { return x.first < y.first; });
      for (const auto& [k, value] : sums) {
        if (!merged.empty() && merged.back().first == k)
          merged.back().second += value;
        else
          merged.emplace_back(k, value);
      }
    }
    contributions[t] = std::move(merged);
    if (!cluster || !cluster->distributed()) progress.advance();
  };
  if (!cluster || !cluster->distributed()) {
    tbb::parallel_for(std::size_t(0), triangles.triangle_count(), integrate_triangle);
  } else {
    // Across ranks: a task per triangle, its per-site sums sent to every rank, which
    // adds them up in triangle order as one process does.
    const auto triangle_bytes = [&](std::size_t t) {
      std::vector<uint32_t> ids;
      std::vector<double> values;
      for (const auto& [k, value] : contributions[t]) ids.push_back(k), values.push_back(value);
      ByteWriter writer;
      writer.put_array(ids);
      writer.put_array(values);
      return writer.take();
    };
    run_task_farm_everywhere(
        *cluster, triangles.triangle_count(),
        [&](std::size_t t) {
          integrate_triangle(t);
          Bytes bytes = triangle_bytes(t);
          std::vector<std::pair<uint32_t, double>>().swap(contributions[t]);
          return bytes;
        },
        [&](std::size_t t, std::span<const std::byte> result) {
          ByteReader reader(result);
          const std::vector<uint32_t> ids = reader.get_array<uint32_t>();
          const std::vector<double> values = reader.get_array<double>();
          contributions[t].clear();
          for (std::size_t e = 0; e < ids.size(); ++e) contributions[t].emplace_back(ids[e], values[e]);
          progress.advance();
        },
        triangle_bytes);
  }
  progress.finish();
  std::vector<double> areas(site_count, 0.0);
  for (const auto& sums : contributions)
    for (const auto& [k, value] : sums) areas[k] += value;
  return areas;
}

}  // namespace candela
