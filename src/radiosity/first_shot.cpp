#include "radiosity/first_shot.h"

#include <tbb/parallel_for.h>

#include <array>
#include <cmath>

#include "scene/direct_irradiance.h"
#include "scene/scene.h"
#include "util/progress.h"

namespace candela {

namespace {

// The point of the element's primitive nearest `point` along the element's normal, with that
// surface's normal turned to the element's side: on a curved shape the flat element lies inside
// (or outside) the true surface, and a shadow ray from the chord would start inside the sphere.
// Flat shapes: the point itself.
void onto_surface(const Shape& shape, const RadiositySurface& element, Vec3& point, Vec3& normal) {
  const double reach = std::sqrt(element.area) + 1e-9;  // the sag of a chord is less than its length
  double nearest = kInfinity;
  SurfaceHit best;
  for (const double side : {1.0, -1.0}) {
    SurfaceHit hit;
    if (shape.intersect(Ray{point, element.normal * side, 0.0, reach}, hit) && hit.t < nearest) {
      nearest = hit.t;
      best = hit;
    }
  }
  if (!std::isfinite(nearest)) return;
  point = best.position;
  normal = dot(best.geometric_normal, element.normal) >= 0 ? best.geometric_normal : -best.geometric_normal;
}

}  // namespace

std::array<Color, 4> direct_irradiance_samples(const Scene& scene, const RadiositySurface& surface,
                                               const StratumJitter& jitter) {
  const auto& [a, b, c] = surface.corners;
  // The centroids of the four triangles of the midpoint subdivision.
  const std::array<Vec3, 4> points = {(a * 4 + b + c) / 6, (a + b * 4 + c) / 6, (a + b + c * 4) / 6,
                                      (a + b + c) / 3};
  const Shape& shape = *scene.primitives[surface.primitive].shape;
  std::array<Color, 4> samples;
  for (std::size_t k = 0; k < 4; ++k) {
    Vec3 point = points[k], normal = surface.normal;
    onto_surface(shape, surface, point, normal);
    samples[k] = direct_irradiance(scene, point, normal, EmitterSet::lights_and_environment, jitter);
  }
  return samples;
}

void shoot_scene_lights(const Scene& scene, RadiosityMesh& mesh, std::span<const uint32_t> elements,
                        uint64_t seed, bool quiet) {
  if (!scene.lights.empty() || scene.environment_light) {
    const StratumJitter jitter{true, seed};
    ProgressReporter progress("direct light", elements.size(), "elements", quiet);
    tbb::parallel_for(std::size_t(0), elements.size(), [&](std::size_t i) {
      RadiositySurface& element = mesh.elements[elements[i]];
      Color sum;
      for (const Color& sample : direct_irradiance_samples(scene, element, jitter)) sum += sample;
      element.first_shot = element.reflectance * sum * 0.25;
      progress.advance();
    });
    progress.finish();
  }
  // Every patch from its elements (a split element's children replace it).
  std::vector<Color> weighted(mesh.patches.size());
  for (std::size_t q = 0; q < mesh.elements.size(); ++q)
    weighted[mesh.patch_of_element[q]] += mesh.elements[q].first_shot * mesh.elements[q].area;
  for (std::size_t p = 0; p < mesh.patches.size(); ++p)
    mesh.patches[p].first_shot = mesh.patches[p].area > 0 ? weighted[p] / mesh.patches[p].area : Color();
}

}  // namespace candela
