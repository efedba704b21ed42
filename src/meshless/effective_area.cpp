#include "meshless/effective_area.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "raster/tessellated_scene.h"
#include "scene/scene.h"

namespace candela {

std::vector<double> integrate_effective_areas(const Scene& scene, const MeshlessBasis& basis, const SiteSet& sites,
                                              double cell, int segments) {
  const std::size_t site_count = sites.sites.size();
  // The sides sites lie on, per object: bit 0 the geometric normal's side, bit 1 the other.
  std::vector<uint8_t> sides_with_sites(scene.objects.size(), 0);
  for (std::size_t i = 0; i < site_count && i < sites.object.size(); ++i)
    if (sites.object[i] < sides_with_sites.size()) sides_with_sites[sites.object[i]] |= sites.side[i] > 0 ? 1 : 2;
  if (!(cell > 0) || !std::isfinite(cell)) throw std::invalid_argument("effective areas: the cell size must be > 0");
  if (segments < 3) throw std::invalid_argument("effective areas: segments must be >= 3");
  TessellationRequest request;
  request.max_segments = segments;
  request.clip = scene.bounds();
  const TessellatedScene triangles = tessellate_scene(scene, request);
  // Per triangle in parallel, each thread summing into its own vector; the per-triangle sums are
  // added in triangle order afterwards, so the result does not depend on the thread count.
  std::vector<std::vector<std::pair<uint32_t, double>>> contributions(triangles.triangle_count());
  tbb::parallel_for(std::size_t(0), triangles.triangle_count(), [&](std::size_t t) {
    const Vec3 a = triangles.corner_positions[3 * t], b = triangles.corner_positions[3 * t + 1],
               c = triangles.corner_positions[3 * t + 2];
    const Vec3 face = cross(b - a, c - a);
    const double area = 0.5 * length(face);
    if (!(area > 0)) return;
    const Vec3 normal = face / (2 * area);
    const uint8_t sides = triangles.objects[t] < sides_with_sites.size() ? sides_with_sites[triangles.objects[t]] : 0;
    if (sides == 0) return;
    // n × n similar sub-triangles (n² of them: n(n+1)/2 upright, n(n−1)/2 inverted), area/n² each.
    const double longest = std::max({length(b - a), length(c - b), length(a - c)});
    const int n = std::max(1, static_cast<int>(std::ceil(longest / cell)));
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
    std::vector<std::pair<uint32_t, double>> sums;
    for (auto& row : rows) sums.insert(sums.end(), row.begin(), row.end());
    contributions[t] = std::move(sums);
  });
  std::vector<double> areas(site_count, 0.0);
  for (const auto& sums : contributions)
    for (const auto& [k, value] : sums) areas[k] += value;
  return areas;
}

}  // namespace candela
