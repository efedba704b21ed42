#include "scene/surface_emitter_index.h"

#include <unordered_map>

#include "scene/scene.h"

namespace candela {

SurfaceEmitterIndex::SurfaceEmitterIndex(const Scene& scene) : scene_(scene) {
  if (scene.surface_lights.empty()) return;
  std::unordered_map<const Shape*, uint32_t> primitive_of;
  for (uint32_t p = 0; p < scene.primitives.size(); ++p) primitive_of.emplace(scene.primitives[p].shape, p);
  light_.assign(scene.primitives.size(), kNone);
  share_.assign(scene.primitives.size(), 0.0);
  for (std::size_t k = 0; k < scene.surface_lights.size(); ++k) {
    const SurfaceLight& light = *scene.surface_lights[k];
    for (const Shape* shape : light.shapes()) {
      const auto found = primitive_of.find(shape);
      if (found == primitive_of.end()) continue;
      light_[found->second] = static_cast<uint32_t>(k);
      share_[found->second] = shape->area() / light.area();
    }
  }
}

double SurfaceEmitterIndex::pdf(uint32_t primitive, const Vec3& from, const SurfaceHit& at) const {
  const double share = share_of(primitive);
  return share > 0 ? share * scene_.primitives[primitive].shape->pdf_from(from, at) : 0.0;
}

}  // namespace candela
