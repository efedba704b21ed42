// The element centres of the meshless method (seed 002 §4.2.6–4.2.7, §5.2.2; SPEC §11): sites
// sampled where the camera and the light's paths look, pruned to a minimum spacing, each with the
// radius of its m nearest neighbours and its effective area.
//
//   1. Camera rays through the centres of a regular grid of the camera's image (grid × grid
//      rays, at least one per pixel row/column of the grid) add their first hits.
//   2. Rounds of secondary rays: from every site, one ray in a cosine-distributed direction about
//      its normal ("a pseudo-random ray whose direction is close to the normal"), adding its hit.
//      After every round the set is pruned.
//   3. Pruning: no two sites closer than Δ (site distance, site.h). Sites are kept greedily in a
//      fixed order — camera sites first, then each round's in the order of the sites that shot
//      them — so a site is dropped when a kept one lies within Δ.
//   4. Radius r_i: the site distance from p_i to its m-th nearest other site (002 §4.2.7; m = 10).
//      Effective area A_i = π h_i²/(m + 1) with h_i = r_i (002 eq. 5.5).
//
// A site's normal is the surface's geometric normal turned toward the ray that found it (the
// side the light travels on). Randomness: one PCG32 stream per (round, shooting site), so the
// result does not depend on the thread count.
#pragma once

#include <cstdint>
#include <vector>

#include "math/vector.h"
#include "meshless/site.h"

namespace candela {

class ProgressReporter;
class Scene;

struct SiteSamplingSettings {
  int grid = 64;        // camera rays per image side
  int rounds = 4;       // rounds of secondary rays
  double spacing = 0;   // Δ, the least site distance between two sites; 0: the scene's size / 50
  int neighbours = 10;  // m
  uint64_t seed = 0;
  std::size_t max_sites = 1u << 22;  // refused beyond (a spacing far too small for the scene)
};

struct SiteSet {
  std::vector<Site> sites;
  std::vector<double> radius;          // r_i = h_i
  std::vector<double> effective_area;  // A_i = π h_i² / (m + 1)
  std::vector<uint32_t> primitive;     // the primitive each site lies on
  std::vector<Color> albedo;           // β(ṗ_i) = the material's kd there, clamped to [0, 1]
  std::vector<Color> emission;         // the material's emitted exitance E there
  std::vector<uint32_t> object;        // the scene object each site lies on
  // +1 when the site's normal is the surface's geometric normal, −1 when it was turned (the
  // side the site lies on, which effective areas integrate over).
  std::vector<int8_t> side;
  double spacing = 0;            // Δ used
  std::size_t camera_sites = 0;  // kept from the camera grid
};

// Δ for the scene: the spacing setting, or the scene's size / 50 when it is 0.
double site_spacing(const Scene& scene, double spacing);

// Samples the sites of a prepared scene seen through its camera; progress, when given, advances
// once for the camera grid and once per round (1 + rounds in all). Throws std::invalid_argument
// for bad settings (grid < 1, rounds < 0, negative spacing, neighbours < 1) or when more than
// max_sites would be kept.
SiteSet sample_sites(const Scene& scene, const SiteSamplingSettings& settings,
                     ProgressReporter* progress = nullptr);

// Per scene object (object_count of them), the sides sites lie on: bit 0 (1) the geometric normal's
// side, bit 1 (2) the other. A side no site lies on — a disc's underside, a room's outer walls — is
// no part of the solution, however far an element's support reaches.
std::vector<uint8_t> sides_with_sites(const SiteSet& set, std::size_t object_count);

// Radii and effective areas for given sites (step 4), m = neighbours: what sample_sites does last,
// for sites placed by other means (tests, a regular lattice).
void assign_radii(SiteSet& set, int neighbours);

}  // namespace candela
