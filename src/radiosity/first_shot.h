// Radiosity's first shot from the scene's lights (issue 19): point, spot, directional and area
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

#include <cstdint>
#include <span>

#include "radiosity/radiosity_mesh.h"

namespace candela {

class Scene;

// Sets first_shot of the listed elements, then of every patch from its elements.
void shoot_scene_lights(const Scene& scene, RadiosityMesh& mesh, std::span<const uint32_t> elements,
                        uint64_t seed, bool quiet);

}  // namespace candela
