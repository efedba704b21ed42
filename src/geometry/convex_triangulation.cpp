#include "geometry/convex_triangulation.h"

namespace candela {

std::vector<std::array<uint32_t, 3>> triangulate_convex_polygon(uint32_t corners) {
  std::vector<std::array<uint32_t, 3>> triangles;
  if (corners < 3) return triangles;
  triangles.reserve(corners - 2);
  const uint32_t third = corners / 3, two_thirds = static_cast<uint32_t>(uint64_t{2} * corners / 3);
  triangles.push_back({0, third, two_thirds});
  // Arcs still to fill, each as its first corner and its number of steps round the polygon (the
  // last arc closes at corner 0); an explicit stack, log₂ corners deep.
  struct Arc {
    uint32_t first, steps;
  };
  std::vector<Arc> arcs{{0, third}, {third, two_thirds - third}, {two_thirds, corners - two_thirds}};
  while (!arcs.empty()) {
    const Arc arc = arcs.back();
    arcs.pop_back();
    if (arc.steps < 2) continue;
    const uint32_t half = arc.steps / 2;
    const uint32_t middle = arc.first + half, last = arc.first + arc.steps;
    triangles.push_back({arc.first, middle, last == corners ? 0 : last});
    arcs.push_back({arc.first, half});
    arcs.push_back({middle, arc.steps - half});
  }
  return triangles;
}

}  // namespace candela
