// The radiosity method's settings (SPEC §10; 000 §6): the "radiosity" object of the scene file,
// read by read_radiosity_settings with ranges checked and unknown keys refused.
#pragma once

#include "io/json_node.h"
#include "util/enum_names.h"
#include "util/error.h"

namespace candela {

// hierarchical: links between quadtree nodes and clusters refined by an oracle (SPEC §10.1,
// radiosity/hierarchical_radiosity.h).
enum class RadiositySolver { progressive, gauss_seidel, gaussian, hierarchical };
// hemicube: 000 §6.4; ray_cast: Lambert's point-to-polygon form factor times the visible fraction
// of ray_cast_samples² rays through the accelerator (radiosity/ray_cast_form_factors.h).
enum class RadiosityFormFactors { hemicube, ray_cast };
// How the solution is shown (000 §6.5): one radiosity per element, or vertex radiosities
// interpolated across each element (Gouraud).
enum class RadiosityDisplay { flat, gouraud, ray_traced, elements };

struct RadiositySettings {
  RadiositySolver solver = RadiositySolver::hierarchical;
  RadiosityFormFactors form_factors = RadiosityFormFactors::hemicube;
  int hemicube_resolution = 100;  // even, ≥ 2 (000 §6.4)
  int ray_cast_samples = 4;       // per side of the source: 16 visibility rays per form factor
  double patch_size = 0;          // the longest patch edge; 0: the scene size / 8
  double element_size = 0;        // the longest element edge; 0: patch_size / 2
  // Tessellation of curved shapes: divisions of a full turn (area-true, geometry/tessellation.h);
  // 32 keeps a sphere's form factors within 0.25 % of Howell's from any side.
  int segments = 32;
  // progressive: stop when the unshot flux is this fraction of the emitted flux (000 §6.6);
  // gauss-seidel: stop when a sweep changes no radiosity by more than this fraction of max B.
  double threshold = 0.001;
  int max_steps = 100000;  // shots (progressive) or sweeps (gauss-seidel) at most
  bool ambient = true;     // progressive: add the ambient term of 000 §6.6.2 for display
  // Ray-traced by default: the Gouraud field (000 §6.5) looked up at each hit, so every aa mode of
  // the scene (the default scene's jittered lattice too) reaches it; gouraud rasterizes.
  RadiosityDisplay display = RadiosityDisplay::ray_traced;
  // Adaptive subdivision (000 §6.7.2): after a solution, every element whose radiosity differs
  // from a neighbour's by more than this fraction of the largest reflected radiosity is split,
  // and the scene solved again, until no pair differs by more (0: off) or the elements reach
  // min_element_size.
  double subdivision_threshold = 0;
  double min_element_size = 0;  // 0: element_size / 8
  // hierarchical: a link (or a leaf's direct light) is refined while the power it may be wrong by
  // exceeds this fraction of the power the scene emits and reflects first.
  double refinement_tolerance = 5e-5;
  // Cut surfaces where other objects meet them before meshing (the remedy for light leaks).
  bool split_at_contacts = false;
  // The memory the stored form factors may take (MiB); 0: half the machine's memory.
  double memory_limit_mib = 0;
  // Where a refusal for memory points — the size key that sets the mesh when the scene
  // gives one (min_element_size, element_size, patch_size), else the "radiosity" object.
  SourceLocation location;
};

inline constexpr auto kRadiositySolverNames =
    enum_names<RadiositySolver>({{RadiositySolver::progressive, "progressive"},
                                 {RadiositySolver::gauss_seidel, "gauss-seidel"},
                                 {RadiositySolver::gaussian, "gaussian"},
                                 {RadiositySolver::hierarchical, "hierarchical"}});
inline constexpr auto kRadiosityFormFactorNames = enum_names<RadiosityFormFactors>(
    {{RadiosityFormFactors::hemicube, "hemicube"}, {RadiosityFormFactors::ray_cast, "ray-cast"}});
inline constexpr auto kRadiosityDisplayNames =
    enum_names<RadiosityDisplay>({{RadiosityDisplay::flat, "flat"},
                                  {RadiosityDisplay::gouraud, "gouraud"},
                                  {RadiosityDisplay::ray_traced, "ray-traced"},
                                  {RadiosityDisplay::elements, "elements"}});

// The "radiosity" object (expected an object; ranges checked, unknown keys refused).
RadiositySettings read_radiosity_settings(const JsonNode& node);

}  // namespace candela
