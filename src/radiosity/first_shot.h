// Radiosity's first shot from the scene's lights: point, spot, directional and area
// lights, and the environment (the sky seen through openings), are not surfaces the hemicube can
// see, so they shoot before the solve — each element's
// direct light, by shadow rays from four points of it (the centroids of its midpoint
// subdivision, a quarter of the area each) to every sample of every light, becomes ρ times that
// light in the element's first_shot, the source term the solvers add to its emission (the
// approach of Lightscape and of Radiance's direct component). B = E + ρ(D + Σ F B) is then solved
// exactly as before; a patch's first shot is the area-weighted mean of its elements'. Emissive
// surfaces stay emitters of the mesh (form factors carry their light), so only the "lights" array
// and the environment shoot here. Opaque shadows but for thin sheets, window panes, which let their
// transmittance through (Scene::transmittance: daylight through glazing). Each element is computed on
// its own (in parallel, each into its own slot), the jitter a function of the point: the result does not
// depend on the thread count.
#pragma once

#include <array>
#include <cstdint>
#include <span>

#include "radiosity/radiosity_mesh.h"
#include "scene/direct_irradiance.h"

namespace candela {

class Scene;

// The direct irradiance of the scene's lights and environment at the centroids of the four
// triangles of the surface's midpoint subdivision (shadow rays from there, on the true surface of
// a curved shape): the samples a first shot averages.
std::array<Color, 4> direct_irradiance_samples(const Scene& scene, const RadiositySurface& surface,
                                               const StratumJitter& jitter);

// Sets first_shot of the listed elements, then of every patch from its elements.
void shoot_scene_lights(const Scene& scene, RadiosityMesh& mesh, std::span<const uint32_t> elements,
                        uint64_t seed, bool quiet);

}  // namespace candela
