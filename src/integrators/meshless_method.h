// The `meshless` method (SPEC §11; seed 002, after Lehtinen et al. 2008): global illumination of
// diffuse surfaces with finite elements defined by points — sites sampled from the camera and by
// rounds of secondary rays (meshless/site_sampling.h), one of three bases over them
// (meshless/meshless_basis.h), a sparse transfer matrix with visibility and effective areas
// (meshless/transfer_matrix.h, meshless/effective_area.h), and the iteration λ ← η + Rλ.
//
// Units: like the radiosity method, radiosity (exitance) B; radiance is B/π. η_i is what site i
// emits (the material's `emission`) plus what it reflects of the lights directly,
// ρ_i Σ_lights I·max(0, n·L)·V, I the light's intensity with its attenuation (the numbers the local
// model's diffuse term uses); ambient light is not a light here.
//
// Display (meshless.display), at the first hit of one ray through each pixel centre, with the site
// p = (hit, the surface normal turned toward the eye):
//   global    Σ λ_i φ_i(p)
//   direct    Σ η_i φ_i(p)                       (the thesis's direct-light figures)
//   indirect  Σ (λ_i − η_i) φ_i(p)
//   hybrid    the direct term traced exactly at the hit (shadow rays per pixel) plus the indirect
//             interpolation — the thesis's proposed future work.
// Pixels that hit nothing, or where no element reaches, show the background.
#pragma once

#include <nlohmann/json.hpp>

#include "integrators/method.h"
#include "meshless/site_sampling.h"
#include "meshless/transfer_matrix.h"

namespace candela {

struct MeshlessSolution {
  SiteSet sites;
  std::vector<Color> eta;      // η: emitted and directly reflected
  TransferSolution transfer;   // λ
  TransferMatrix matrix;       // S
  double sampling_seconds = 0, area_seconds = 0, solve_seconds = 0;
};

// Samples, builds and solves (quiet: no progress output); fills facts for --stats when given.
MeshlessSolution solve_meshless(const Scene& scene, nlohmann::json* facts = nullptr);

class MeshlessMethod final : public Method {
 public:
  std::string_view name() const override { return "meshless"; }
  void render(const Scene& scene, const RenderRequest& request, Film& film,
              RunStatistics& statistics) const override;
};

}  // namespace candela
