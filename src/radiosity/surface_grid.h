// A hash grid over the triangles of a radiosity mesh, for finding the surfaces near a point or a
// box without scanning them all: the element under a ray's hit (RadiosityMesh::element_at, once
// per pixel of the ray-cast displays) and the neighbours of an element (adaptive subdivision).
//
// Cells are cubes as large as the longest triangle edge, so a triangle overlaps at most 2 cells
// along each axis; each triangle is listed in every cell its box (grown by the margin) overlaps.
#pragma once

#include <cstdint>
#include <unordered_map>
#include <vector>

#include "math/bounds.h"

namespace candela {

struct RadiositySurface;

class SurfaceGrid {
 public:
  SurfaceGrid() = default;
  // margin: how far outside its box a triangle still counts as overlapping a cell.
  SurfaceGrid(const std::vector<RadiositySurface>& surfaces, double margin);

  double cell_size() const { return cell_; }
  const Bounds3& bounds() const { return bounds_; }  // of every surface
  bool empty() const { return cells_.empty(); }

  // Calls visit(index) for every surface listed in a cell that box (grown by the margin)
  // overlaps; a surface may be visited more than once.
  template <typename Visit>
  void for_each_near(const Bounds3& box, Visit&& visit) const {
    if (cells_.empty()) return;
    const CellRange range = cells_of(box);
    for (int64_t x = range.lower[0]; x <= range.upper[0]; ++x)
      for (int64_t y = range.lower[1]; y <= range.upper[1]; ++y)
        for (int64_t z = range.lower[2]; z <= range.upper[2]; ++z) {
          const auto found = cells_.find(key(x, y, z));
          if (found == cells_.end()) continue;
          for (const uint32_t index : found->second) visit(index);
        }
  }

 private:
  struct CellRange {
    int64_t lower[3], upper[3];
  };
  CellRange cells_of(const Bounds3& box) const;
  static uint64_t key(int64_t x, int64_t y, int64_t z);

  double cell_ = 1, margin_ = 0;
  Vec3 origin_;
  Bounds3 bounds_;
  std::unordered_map<uint64_t, std::vector<uint32_t>> cells_;
};

}  // namespace candela
