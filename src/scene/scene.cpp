#include "scene/scene.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "accel/accelerator_registry.h"
#include "scene/environment_light.h"
#include "shading/environment.h"
#include "shading/material_bsdf.h"

namespace candela {

namespace {
std::atomic<uint64_t> next_scene_id{1};
}  // namespace

Scene::Scene() : unique_id(next_scene_id.fetch_add(1)) {}
Scene::~Scene() = default;

Color Scene::background_along(const Vec3& direction) const {
  if (!environment) return background;
  // An image may hold negative values (a processed EXR): radiance is kept >= 0.
  const Color c = environment->radiance(direction);
  return {c.r > 0 ? c.r : 0.0, c.g > 0 ? c.g : 0.0, c.b > 0 ? c.b : 0.0};
}

Color Scene::sky_along(const Vec3& direction) const {
  return environment ? background_along(direction) : Color();
}

bool Scene::intersect_past_sheets(Ray ray, Intersection& hit, Color& through) const {
  through = Color(1);
  if (!thin_sheets_) return intersect(ray, hit);
  for (int sheet = 0; sheet <= kMaxSheetsCrossed; ++sheet) {
    if (!intersect(ray, hit)) return false;
    const Material& material = material_of(hit);
    if (!(material.thin && material.has_refraction())) return true;
    through *= thin_sheet_transmittance(material, hit.surface, ray.direction);
    ray.t_min = hit.surface.t + ray_offset(hit.surface.position);
    if (through.is_black()) return true;
    if (!(ray.t_min < ray.t_max)) return false;
  }
  through = Color(0);
  return true;
}

Color Scene::transmittance(const Ray& ray) const {
  if (!thin_sheets_) return Color(occluded(ray) ? 0.0 : 1.0);
  Intersection hit;
  Color through;
  return intersect_past_sheets(ray, hit, through) ? Color(0) : through;
}

void Scene::prepare() {
  thin_sheets_ = lets_light_through_ = false;
  for (Material& material : materials) {
    material.prepare();
    thin_sheets_ = thin_sheets_ || (material.thin && material.has_refraction());
    lets_light_through_ = lets_light_through_ || material.lets_light_through();
  }
  if (environment) {
    environment->prepare_sampling();
    environment_light = std::make_unique<EnvironmentLight>(*environment, render.environment_light_samples);
  }
  const AcceleratorEntry* entry = find_accelerator(render.accelerator);
  if (!entry)
    throw std::invalid_argument("unknown accelerator " + render.accelerator);  // checked by the loader
  const auto start = std::chrono::steady_clock::now();
  accelerator_ = entry->create(plugin_settings.node(entry->name), render.bounding_volume);
  accelerator_->build(primitives);
  build_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  for (std::string& warning : accelerator_->report().warnings) warnings.push_back(std::move(warning));
  bounds_ = Bounds3();
  for (const Primitive& primitive : primitives) {
    const Bounds3 b = primitive.shape->bounds();
    if (b.is_finite()) bounds_.extend(b);
  }
  if (bounds_.empty()) bounds_ = Bounds3::of_point({0, 0, 0});
  const Vec3 extent = bounds_.diagonal();
  const double size = std::max({extent.x, extent.y, extent.z});
  // The extent part of ray_offset(p); its position part covers scenes far from the origin.
  ray_offset_ = render.ray_offset > 0 ? render.ray_offset : 1e-7 * size;
  offset_per_position_ = 1e-12 + accelerator_->position_error();
}

}  // namespace candela
