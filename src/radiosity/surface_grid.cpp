#include "radiosity/surface_grid.h"

#include <algorithm>
#include <cmath>

#include "radiosity/radiosity_mesh.h"

namespace candela {

SurfaceGrid::SurfaceGrid(const std::vector<RadiositySurface>& surfaces, double margin) : margin_(margin) {
  if (surfaces.empty()) return;
  Bounds3 bounds;
  std::vector<double> edges(surfaces.size());
  double smallest = 0, largest = 0;
  for (std::size_t i = 0; i < surfaces.size(); ++i) {
    for (const Vec3& corner : surfaces[i].corners) bounds.extend(corner);
    edges[i] = longest_edge(surfaces[i]);
    if (edges[i] > 0) smallest = smallest > 0 ? std::min(smallest, edges[i]) : edges[i];
    largest = std::max(largest, edges[i]);
  }
  if (!(largest > 0)) smallest = largest = 1;
  // At most 24 levels (a factor of 2²³ between the smallest and the largest cell): smaller
  // triangles share the first level.
  const int count = std::clamp(static_cast<int>(std::ceil(std::log2(largest / smallest))) + 1, 1, 24);
  levels_.resize(static_cast<std::size_t>(count));
  for (int l = 0; l < count; ++l)
    levels_[static_cast<std::size_t>(l)].cell = largest / std::ldexp(1.0, count - 1 - l);
  origin_ = bounds.lower;
  bounds_ = bounds;
  for (uint32_t i = 0; i < surfaces.size(); ++i) {
    std::size_t l = 0;
    while (l + 1 < levels_.size() && levels_[l].cell < edges[i]) ++l;
    Level& level = levels_[l];
    Bounds3 box;
    for (const Vec3& corner : surfaces[i].corners) box.extend(corner);
    const CellRange range = cells_of(level, box);
    for (int64_t x = range.lower[0]; x <= range.upper[0]; ++x)
      for (int64_t y = range.lower[1]; y <= range.upper[1]; ++y)
        for (int64_t z = range.lower[2]; z <= range.upper[2]; ++z) level.cells[key(x, y, z)].push_back(i);
  }
}

SurfaceGrid::CellRange SurfaceGrid::cells_of(const Level& level, const Bounds3& box) const {
  CellRange range;
  for (int axis = 0; axis < 3; ++axis) {
    // Clamped so that far-away queries cannot overflow; keys wrap at 2^21 cells per axis.
    const auto cell = [&](double value) {
      return static_cast<int64_t>(std::clamp(std::floor((value - origin_[axis]) / level.cell), -1e6, 1e6));
    };
    range.lower[axis] = cell(box.lower[axis] - margin_);
    range.upper[axis] = cell(box.upper[axis] + margin_);
  }
  return range;
}

uint64_t SurfaceGrid::key(int64_t x, int64_t y, int64_t z) {
  return (static_cast<uint64_t>(x) & 0x1FFFFF) | (static_cast<uint64_t>(y) & 0x1FFFFF) << 21 |
         (static_cast<uint64_t>(z) & 0x1FFFFF) << 42;
}

}  // namespace candela
