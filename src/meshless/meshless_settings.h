// The scene file's "meshless" object (SPEC §11, seed 002): how the sites are sampled, the basis
// over them, the effective areas, the transfer, the iteration and the display.
#pragma once

#include "io/json_node.h"
#include "meshless/meshless_basis.h"
#include "util/enum_names.h"
#include "util/error.h"

namespace candela {

// How the solution is shown (see above).
enum class MeshlessDisplay { global, direct, indirect, hybrid };
inline constexpr auto kMeshlessDisplayNames =
    enum_names<MeshlessDisplay>({{MeshlessDisplay::global, "global"},
                                 {MeshlessDisplay::direct, "direct"},
                                 {MeshlessDisplay::indirect, "indirect"},
                                 {MeshlessDisplay::hybrid, "hybrid"}});
// The sites' effective areas: integrated over the surfaces (meshless/effective_area.h), or the
// thesis's πh²/(m + 1).
enum class MeshlessAreas { integrated, thesis };
inline constexpr auto kMeshlessAreaNames =
    enum_names<MeshlessAreas>({{MeshlessAreas::integrated, "integrated"}, {MeshlessAreas::thesis, "thesis"}});

// The transfer: the thesis's flat matrix, every far element on its own (n² entries at worst), or
// the hierarchical transport of Lehtinen et al. 2008 (links between nodes of the site
// hierarchy, O(n log n) entries at worst; meshless/site_hierarchy.h, meshless/transfer_matrix.h).
enum class MeshlessTransport { flat, hierarchical };
inline constexpr auto kMeshlessTransportNames = enum_names<MeshlessTransport>(
    {{MeshlessTransport::flat, "flat"}, {MeshlessTransport::hierarchical, "hierarchical"}});

// The scene file's "meshless" object (SPEC §11, seed 002).
struct MeshlessSettings {
  BasisKind basis = BasisKind::normalized;
  RadialKernel kernel = RadialKernel::gaussian;  // the radial basis's mother function
  double spacing = 0;   // Δ: no two sites closer (site distance); 0: the scene's size / 50
  int neighbours = 10;  // m: the radius holds the m nearest sites
  int grid = 64;        // camera rays per image side for the first sites
  int rounds = 4;       // rounds of secondary rays
  MeshlessAreas effective_area = MeshlessAreas::integrated;
  double tolerance = 1e-4;  // the iteration stops when no coefficient changes by more (relative)
  int max_iterations = 1000;
  MeshlessDisplay display = MeshlessDisplay::global;
  double shepard_power = 2;
  int max_sites = 50000;  // refused beyond: the transfer matrix grows as n²
  int gather_rays = 256;  // per site, for the transfer matrix's near field (meshless/transfer_matrix.h)
  double near_field = 2;  // the near field: elements closer than this many of their radii
  MeshlessTransport transport = MeshlessTransport::flat;
  double cluster_angle = 0.15;  // hierarchical: two nodes are linked while extent/distance < this
  // Where a refusal of the sites or the transfer matrix (too many, too much memory)
  // points — the spacing when the scene gives it, else the "meshless" object.
  SourceLocation location;
};
// Ranges checked, unknown keys refused.
MeshlessSettings read_meshless_settings(const JsonNode& node);

}  // namespace candela
