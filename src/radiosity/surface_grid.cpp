#include "radiosity/surface_grid.h"

#include <algorithm>
#include <cmath>

#include "radiosity/radiosity_mesh.h"

namespace candela {

SurfaceGrid::SurfaceGrid(const std::vector<RadiositySurface>& surfaces, double margin) : margin_(margin) {
  if (surfaces.empty()) return;
  Bounds3 bounds;
  double longest_edge = 0;
  for (const RadiositySurface& surface : surfaces)
    for (int k = 0; k < 3; ++k) {
      bounds.extend(surface.corners[k]);
      longest_edge = std::max(longest_edge, length(surface.corners[(k + 1) % 3] - surface.corners[k]));
    }
  cell_ = longest_edge > 0 ? longest_edge : 1;
  origin_ = bounds.lower;
  bounds_ = bounds;
  for (uint32_t i = 0; i < surfaces.size(); ++i) {
    Bounds3 box;
    for (const Vec3& corner : surfaces[i].corners) box.extend(corner);
    const CellRange range = cells_of(box);
    for (int64_t x = range.lower[0]; x <= range.upper[0]; ++x)
      for (int64_t y = range.lower[1]; y <= range.upper[1]; ++y)
        for (int64_t z = range.lower[2]; z <= range.upper[2]; ++z) cells_[key(x, y, z)].push_back(i);
  }
}

SurfaceGrid::CellRange SurfaceGrid::cells_of(const Bounds3& box) const {
  CellRange range;
  for (int axis = 0; axis < 3; ++axis) {
    // Clamped so that far-away queries cannot overflow; keys wrap at 2^21 cells per axis.
    const auto cell = [&](double value) {
      return static_cast<int64_t>(std::clamp(std::floor((value - origin_[axis]) / cell_), -1e6, 1e6));
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
