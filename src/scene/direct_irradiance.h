// What a surface point receives straight from the emitters, with opaque shadows but for window panes:
// the sum over every sample of the chosen emitters of I · max(0, n·L) · V (V = 0 when something
// opaque lies between, the thin sheets' transmittance otherwise: Scene::transmittance) — the
// irradiance, in the units in which a diffuse surface of reflectance ρ reflects ρ times it. One
// implementation for the methods that light diffuse points from the lights: meshless η (seed 002
// §4.3, the hybrid method's direct part) and radiosity's first shot (point, spot,
// directional and area lights light each element, the approach of Lightscape and of Radiance's
// direct component). The local model's own loop (integrators/direct_lighting.h) adds transparent
// shadows and the specular term.
#pragma once

#include "math/pcg32.h"
#include "math/vector.h"
#include "scene/light.h"

namespace candela {

class Scene;
class SurfaceEmitterIndex;

// Rays besides the lights' samples for the emissive surfaces: `rays` cosine-distributed
// directions about the normal, drawn from `random`. A ray that hits an emissive surface adds its
// emission, and both it and that surface's light samples are weighed by the power heuristic
// (Veach 1997 §9.2, the sample counts in the densities), so a point beside a large emitter — a
// glowing room's wall next to its neighbour, where a light sample's 1/d² makes the estimate
// spiky and its mean unreliable — is lit as smoothly as one far from it, and a small emitter
// keeps its light samples. The environment and the other lights keep their samples alone.
struct HemisphereRays {
  const SurfaceEmitterIndex& emitters;
  int rays = 0;
  Pcg32& random;
};

enum class EmitterSet {
  lights,                  // the "lights" array alone (what rays cannot hit: probe's sensors)
  lights_and_environment,  // and the environment (radiosity meshes the emissive surfaces as
                           // emitters of its own)
  everything,              // the lights, the emissive surfaces and the environment (Scene::emitter)
};

Color direct_irradiance(const Scene& scene, const Vec3& point, const Vec3& normal, EmitterSet emitters,
                        const StratumJitter& jitter, const HemisphereRays* hemisphere = nullptr);

}  // namespace candela
