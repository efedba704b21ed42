// Effective areas of the meshless elements (seed 002 §5.2.2): A_k = ∫ φ_k(q) dq over the sites of
// the scene (eq. 5.3), which for a partition of unity add up to the area the elements cover
// (eq. 5.4). Two estimates:
//   - the thesis's A_k = π h_k²/(m + 1) (eq. 5.5, meshless/site_sampling.h), which supposes the
//     surface flat and the sites evenly spread within h_k, and overestimates by 5–10 % on
//     evenly spread sites (tested);
//   - integrate_effective_areas: eq. 5.3 itself by the midpoint rule over the scene's surfaces
//     cut into triangles no longer than `cell` on a side. Each side of a surface is a set of
//     sites of its own (a wall lit from both sides has elements on both), so every sample counts
//     with both normals.
#pragma once

#include <vector>

#include "meshless/meshless_basis.h"

namespace candela {

class Scene;

// Throws std::invalid_argument unless cell > 0 and segments ≥ 3.
std::vector<double> integrate_effective_areas(const Scene& scene, const MeshlessBasis& basis, std::size_t site_count,
                                              double cell, int segments = 64);

}  // namespace candela
