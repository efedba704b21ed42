// What the meshless method shows along a camera ray (SPEC §11, seed 002; meshless.display), at
// the first hit, with the site p = (hit, the surface normal turned toward the eye):
//   global    Σ λ_i φ_i(p)
//   direct    Σ η_i φ_i(p)                       (the thesis's direct-light figures)
//   indirect  Σ (λ_i − η_i) φ_i(p)
//   hybrid    the direct term traced exactly at the hit (shadow rays per pixel) plus the indirect
//             interpolation — the thesis's proposed future work.
// An emitter is drawn with its own emission (λ and η hold only reflected light). A ray that hits
// nothing, or a point no element reaches, shows the background.
#pragma once

#include <cstdint>
#include <vector>

#include "math/ray.h"
#include "math/vector.h"
#include "meshless/meshless_basis.h"
#include "meshless/meshless_settings.h"

namespace candela {

class Scene;
class SurfaceEmitterIndex;

// eta, lambda: η and λ per site (the lighting's, or an iteration's for the convergence log); seed:
// the render's, which jitters the hybrid display's light samples.
Color meshless_display_radiance(const Scene& scene, const MeshlessSettings& settings,
                                const MeshlessBasis& basis, const std::vector<Color>& eta,
                                const std::vector<Color>& lambda, const SurfaceEmitterIndex& emitters,
                                uint64_t seed, const Ray& ray);

}  // namespace candela
