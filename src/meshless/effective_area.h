// Effective areas of the meshless elements (seed 002 §5.2.2): A_k = ∫ φ_k(q) dq over the sites of
// the scene (eq. 5.3), which for a partition of unity add up to the area the elements cover
// (eq. 5.4). Two estimates:
//   - the thesis's A_k = π h_k²/(m + 1) (eq. 5.5, meshless/site_sampling.h), which supposes the
//     surface flat and the sites evenly spread within h_k, and overestimates by 5–10 % on
//     evenly spread sites (tested);
//   - integrate_effective_areas: eq. 5.3 by the midpoint rule over the scene's surfaces cut into
//     triangles no longer than `cell` on a side, over the sides that sites lie on: each side of
//     each object is a set of sites of its own (a wall seen from both sides has elements on both),
//     and a side no site lies on — a disc's underside, a room's outer walls — is no part of the
//     solution, however far an element's support reaches. The weights are the basis's own
//     normalised, φ_k / Σ_j φ_j: for the partitions of unity that is φ_k itself, and for the
//     radial basis (not a partition of unity; ∫ φ_k is about 2π r_k², twenty times the element's
//     share of the surface at m = 10) it is the share of the surface element k stands for, so
//     the areas still add up to the surface (eq. 5.4).
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "meshless/meshless_basis.h"
#include "meshless/site_sampling.h"
#include "raster/tessellated_scene.h"

namespace candela {

class Cluster;
class Scene;

// cell widens when the surfaces would need more than about 4 million midpoints. Throws
// std::invalid_argument unless cell > 0 and segments ≥ 3. With a cluster of several ranks the
// triangles are shared out among them; every rank gets the same areas as one process. Unless
// quiet, a progress bar counts the triangles.
// What integrate_effective_areas holds at its peak per triangle of the tessellated scene,
// for the method's memory estimate: the triangle three times (its arrays grow by doubling, and a
// reallocation holds the old and the new array), and its per-site sums (four entries and the
// allocation's own header). Measured: 800 spheres of scenes/sphere-field-10584.json, 3,174,400
// triangles, peaked at 3.07 GB resident, 967 bytes a triangle; this gives 1,004.
inline constexpr std::size_t kEffectiveAreaTriangleBytes = 3 * kTessellatedTriangleBytes +
                                                           sizeof(std::vector<std::pair<uint32_t, double>>) +
                                                           16 + 4 * sizeof(std::pair<uint32_t, double>);

// The tessellation the integration runs over, before its planes are cut around the sites: at most
// `segments` per turn, and curved shapes by chord error — chords within half a cell of the surface,
// the midpoint rule's own resolution (the 10,584 small spheres of sphere-field-10584.json
// were 42 M triangles at 64 segments each, and 24 GB). The tessellation is area-true
// (geometry/tessellation.h), so a coarse one still has the shape's area (eq. 5.4).
TessellationRequest effective_area_tessellation(const Scene& scene, double cell, int segments);

std::vector<double> integrate_effective_areas(const Scene& scene, const MeshlessBasis& basis,
                                              const SiteSet& sites, double cell, int segments = 64,
                                              Cluster* cluster = nullptr, bool quiet = true);

}  // namespace candela
