// A view-independent solution (classic radiosity, meshless) asked for the exitance B that leaves a
// surface point — what `candela probe` gathers over a hemisphere to find the irradiance at a
// sensor point (SPEC "Product surface": probe, like Radiance's rtrace -I).
#pragma once

#include <memory>

#include "scene/scene.h"

namespace candela {

struct MeshlessSettings;
struct RadiositySettings;

class SolutionField {
 public:
  virtual ~SolutionField() = default;
  // B (display units: exitance, radiance × π) leaving the surface at hit toward the ray's
  // origin; false when the solution does not cover that point (off the mesh, no site near).
  virtual bool exitance(const Ray& ray, const Intersection& hit, Color& exitance) const = 0;
  // The irradiance the scene's lights (point, spot, directional, area: rays never hit them) give
  // the sensor at point facing normal, in the solution's own model (emissive surfaces and the
  // environment are found by the gathering rays).
  virtual Color direct_irradiance(const Vec3& point, const Vec3& normal) const = 0;
};

// The radiosity solution with these settings, solved now (quiet: no progress bar). `seed`: the
// solve's and the direct light's (the probe's own, not render.seed).
std::unique_ptr<SolutionField> make_radiosity_field(const Scene& scene, const RadiositySettings& settings,
                                                    bool quiet, uint64_t seed);
// The meshless solution with these settings (its sites are sampled from the scene's camera: points
// the camera never sees may have no site near them), with `seed` as the radiosity field's; refused
// (InputError) before any work past render.memory_limit_mib.
std::unique_ptr<SolutionField> make_meshless_field(const Scene& scene, const MeshlessSettings& settings,
                                                   uint64_t seed);

}  // namespace candela
