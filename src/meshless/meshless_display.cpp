#include "meshless/meshless_display.h"

#include "meshless/meshless_solve.h"
#include "scene/scene.h"

namespace candela {

Color meshless_display_radiance(const Scene& scene, const MeshlessSettings& settings,
                                const MeshlessBasis& basis, const std::vector<Color>& eta,
                                const std::vector<Color>& lambda, const SurfaceEmitterIndex& emitters,
                                uint64_t seed, const Ray& ray) {
  thread_local std::vector<std::pair<uint32_t, double>> weights;
  Intersection hit;
  Color color = scene.background_along(ray.direction);
  if (!scene.intersect(ray, hit)) return color;
  const Site p{hit.surface.position, face_forward(hit.surface.geometric_normal, -ray.direction)};
  basis.evaluate(p, weights);
  Color global, direct;
  for (const auto& [i, phi] : weights) {
    global += lambda[i] * phi;
    direct += eta[i] * phi;
  }
  // An emitter is drawn with its own emission (λ and η hold only reflected light).
  const Material& material = scene.material_of(hit);
  switch (settings.display) {
    case MeshlessDisplay::global:
      color = material.emission + global;
      break;
    case MeshlessDisplay::direct:
      color = material.emission + direct;
      break;
    case MeshlessDisplay::indirect:
      color = global - direct;
      break;
    case MeshlessDisplay::hybrid: {
      const Color albedo = material.at(hit.surface).diffuse_albedo();
      // Per pixel the light's samples alone, as the local model draws direct light.
      color = material.emission +
              site_direct_light(scene, emitters, seed, 0, 0, p.position, p.normal, albedo) +
              (global - direct);
      break;
    }
  }
  if (weights.empty() && settings.display != MeshlessDisplay::hybrid)
    color = scene.background_along(ray.direction);
  return color;
}

}  // namespace candela
