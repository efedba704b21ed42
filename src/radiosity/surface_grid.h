// A hash grid over the triangles of a radiosity mesh, for finding the surfaces near a point or a
// box without scanning them all: the element under a ray's hit (RadiosityMesh::element_at, once
// per pixel of the ray-cast displays) and the neighbours of an element (adaptive subdivision).
//
// Levels of cells, cubes whose size doubles from one level to the next: each triangle is listed in
// the level whose cells are at least as large as its longest edge (so it overlaps at most 2 cells
// along each axis), in every cell its box (grown by the margin) overlaps. One level when the
// triangles are alike; many when they are not — hierarchical radiosity's leaves run from a wall's
// metre to a dragon's millimetre, and one level sized by the largest would list thousands of the
// small ones in each cell.
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

  double cell_size() const { return levels_.empty() ? 1 : levels_.back().cell; }  // the largest
  double smallest_cell_size() const { return levels_.empty() ? 1 : levels_.front().cell; }
  const Bounds3& bounds() const { return bounds_; }  // of every surface
  bool empty() const { return levels_.empty(); }

  // Calls visit(index) for every surface listed in a cell that box (grown by the margin)
  // overlaps; a surface may be visited more than once. Every surface whose box (grown by the
  // margin) overlaps `box` is visited.
  template <typename Visit>
  void for_each_near(const Bounds3& box, Visit&& visit) const {
    for (const Level& level : levels_) {
      if (level.cells.empty()) continue;
      const CellRange range = cells_of(level, box);
      for (int64_t x = range.lower[0]; x <= range.upper[0]; ++x)
        for (int64_t y = range.lower[1]; y <= range.upper[1]; ++y)
          for (int64_t z = range.lower[2]; z <= range.upper[2]; ++z) {
            const auto found = level.cells.find(key(x, y, z));
            if (found == level.cells.end()) continue;
            for (const uint32_t index : found->second) visit(index);
          }
    }
  }

 private:
  struct CellRange {
    int64_t lower[3], upper[3];
  };
  struct Level {
    double cell = 1;
    std::unordered_map<uint64_t, std::vector<uint32_t>> cells;
  };
  CellRange cells_of(const Level& level, const Bounds3& box) const;
  static uint64_t key(int64_t x, int64_t y, int64_t z);

  double margin_ = 0;
  Vec3 origin_;
  Bounds3 bounds_;
  std::vector<Level> levels_;  // cell sizes doubling
};

}  // namespace candela
