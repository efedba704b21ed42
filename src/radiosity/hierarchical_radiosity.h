// Hierarchical radiosity with clustering (SPEC §10.1): radiosity.solver "hierarchical".
//
// Links j → i between nodes of the hierarchy (radiosity_hierarchy.h) at any level carry the
// factor by which the source's radiosity (a surface) or intensity (a cluster) becomes irradiance
// at the receiver:
//   surface → surface   F_ij V_ij: Lambert's point-to-polygon factor (point_to_polygon_form_factor)
//                       at the centroids of the receiver's four children, averaged (exact without
//                       occluders at each point), times the visible fraction of four rays;
//   surface → cluster   A_j cosθ_j V / (π r²): the flux density at the cluster, which keeps it by
//                       direction (band-2 spherical harmonics) for each surface inside to take by
//                       its own cosine;
//   cluster → surface   cosθ_i V / r², times the cluster's intensity toward i: Σ (B_k A_k / π)
//                       max(0, n_k·ω) over the surfaces inside, held in spherical harmonics;
//   cluster → cluster   V / r².
// A cluster's visibility rays start and end on surfaces inside that face the other end.
//
// Refinement (Hanrahan et al.'s BF oracle): a link whose power uncertainty ρ_i A_i B_j ΔK exceeds
// ε = refinement_tolerance × the power the scene emits and reflects first (ΔK: the spread of the
// factor over the receiver's points, the whole factor where visibility is partial, and the bound
// 1/r² where a cluster's orientation is unknown) is replaced by links from the children of the
// receiver or of the source (the larger; the receiver where the factor varies over it), down to
// min_element_size; clusters closer than their bounding spheres' radii are always split. A leaf
// whose direct light varies by more than ε of power over its four sample points is split too. After
// each solve the links are refined again with the new radiosities, until none splits (3 rounds at
// most).
//
// Solve (Jacobi over links): gather every link's irradiance at its receiver, push it down to the
// leaves (a cluster's by each surface's cosine), B = E + first shot + ρ E at the leaves, pull
// area-weighted means (surfaces) and intensities (clusters) back up; until no leaf changes by more
// than radiosity.threshold of the largest B. Gather is parallel over receivers, each summing its
// links in a fixed order; refinement decides in parallel and splits in link order; every ray's
// jitter comes from the link's own stream: the solution does not depend on the thread count.
// Several ranks each solve the whole hierarchy (the same on every rank; the display's tiles are
// what they share).
//
// The result is an ordinary RadiositySolveResult: the input triangles are its patches and the
// leaves its elements, so every display, probe and export reads it as any other solution.
#pragma once

#include "radiosity/radiosity_settings.h"
#include "radiosity/radiosity_solve_result.h"

namespace candela {

class Scene;
struct RadiositySolveOptions;

RadiositySolveResult solve_hierarchical_radiosity(const Scene& scene, const RadiositySettings& settings,
                                                  const RadiositySolveOptions& options);

}  // namespace candela
