// The radiosity solution as a SolutionField (integrators/solution_field.h) for `candela probe`.
#include <memory>
#include <utility>

#include "integrators/radiosity_method.h"
#include "integrators/solution_field.h"
#include "radiosity/display.h"
#include "radiosity/solve.h"
#include "radiosity/vertex_radiosity.h"
#include "scene/direct_irradiance.h"

namespace candela {
namespace {

// The ray-traced display's field: the vertex radiosities interpolated over the element hit.
class RadiosityField final : public SolutionField {
 public:
  RadiosityField(const Scene& scene, RadiositySolveResult solution, uint64_t seed)
      : scene_(scene),
        solution_(std::move(solution)),
        vertices_(compute_vertex_radiosity(solution_.mesh.elements, solution_.element_radiosity,
                                           solution_.element_hidden)),
        seed_(seed) {}
  bool exitance(const Ray& ray, const Intersection& hit, Color& exitance) const override {
    const uint32_t element = solution_.mesh.element_at(hit.primitive, hit.surface.position, -ray.direction);
    if (element == UINT32_MAX) return false;
    // Patches are one-sided (000 §6): nothing leaves a patch's back.
    if (dot(ray.direction, solution_.mesh.elements[element].normal) > 0) {
      exitance = Color();
      return true;
    }
    exitance = ray_traced_radiosity(solution_, vertices_, element, hit);
    return true;
  }
  // What rays cannot hit: the lights, as the first shot lit the elements (radiosity/first_shot.h).
  Color direct_irradiance(const Vec3& point, const Vec3& normal) const override {
    return candela::direct_irradiance(scene_, point, normal, EmitterSet::lights, StratumJitter{true, seed_});
  }

 private:
  const Scene& scene_;
  RadiositySolveResult solution_;
  VertexRadiosity vertices_;
  uint64_t seed_;
};

}  // namespace

std::unique_ptr<SolutionField> make_radiosity_field(const Scene& scene, const RadiositySettings& settings,
                                                    bool quiet, uint64_t seed) {
  RadiositySolveOptions options;
  options.seed = seed;
  options.quiet = quiet;
  return std::make_unique<RadiosityField>(scene, solve_radiosity(scene, settings, options), seed);
}

}  // namespace candela
