// Everything a method reads: geometry, materials, lights, camera, and the raw settings objects
// that each method and accelerator reads itself. Methods never edit it (SPEC "Architecture").
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "accel/accelerator.h"
#include "accel/bounding_volume.h"
#include "camera/antialiasing.h"
#include "camera/camera.h"
#include "camera/tone_map.h"
#include "scene/light.h"
#include "scene/plugin_settings.h"
#include "scene/surface_light.h"
#include "shading/material.h"
#include "util/error.h"

namespace candela {

// The most thin sheets (window panes) a ray or a path goes straight through: never loop forever
// on pathological input.
inline constexpr int kMaxSheetsCrossed = 256;

struct RenderSettings {
  std::string method = "whitted";
  SourceLocation method_location;
  uint64_t seed = 0;
  std::string accelerator = "bvh";
  // The list accelerator tests each scene object's volume before its primitives.
  BoundingVolumeKind bounding_volume = BoundingVolumeKind::none;
  double ray_offset = 0;  // 0: derived from the scene's extent (see Scene::ray_offset)
  int tile_size = 16;
  int surface_light_samples = 4;      // per side: an emissive surface's samples² shadow rays
  int environment_light_samples = 4;  // per side: the environment's samples² shadow rays
  // What a method may hold before it is refused (MiB; 0: half the machine's memory),
  // and where the scene sets it (empty when it does not).
  double memory_limit_mib = 0;
  SourceLocation memory_limit_location;
};

// One entry of the scene file's "shapes" array.
struct SceneObject {
  std::string name;
  std::string type;
  uint32_t first_primitive = 0;
  uint32_t primitive_count = 0;
  // The shape's "two_sided": classic radiosity meshes both sides (each gathers and
  // shoots on its own side); the other methods are two-sided already.
  bool two_sided = false;
};

// One entry of the scene file's "cameras" array: another view of the same scene, chosen with
// `candela render --camera NAME`. The name goes into output file names.
struct NamedCamera {
  std::string name;
  std::unique_ptr<Camera> camera;
};

class Environment;

// An emissive object whose surface cannot be sampled (an unbounded plane): the methods that light
// emissive surfaces by shadow rays refuse the scene, naming it.
struct UnsampledEmitter {
  std::string name;  // the object's
  std::string type;  // its shape type
  SourceLocation location;
};

class Scene {
 public:
  Scene();
  ~Scene();
  // Different for every Scene object made by this process: what a method that keeps a
  // view-independent solution between views (radiosity) recognises its scene by.
  const uint64_t unique_id;
  std::string source;  // file name, or "<built-in>"
  // The files the scene file referenced (meshes, textures, environment maps), in load order:
  // what besides the scene file decides the image (path-tracing checkpoints hash them).
  std::vector<std::string> input_files;
  // The camera methods render through: the "camera" object, unless the caller swapped in one
  // of the named cameras for a view (candela render --camera).
  std::unique_ptr<Camera> camera;
  std::vector<NamedCamera> cameras;  // the "cameras" array, in file order
  std::vector<std::unique_ptr<Shape>> shapes;
  std::vector<Primitive> primitives;
  std::vector<SceneObject> objects;
  std::vector<Material> materials;
  std::vector<std::unique_ptr<Light>> lights;  // the "lights" array
  // The emissive objects as lights (surface_light.h), made by the loader.
  std::vector<std::unique_ptr<SurfaceLight>> surface_lights;
  std::vector<UnsampledEmitter> unsampled_emitters;
  // The environment as a light (environment_light.h), made by prepare() when there is one.
  std::unique_ptr<Light> environment_light;
  // Every emitter a shadow ray can aim at: the lights, the surface lights, then the environment
  // (relighting swaps `lights`, so this is counted, never cached).
  std::size_t emitter_count() const {
    return lights.size() + surface_lights.size() + (environment_light ? 1 : 0);
  }
  const Light& emitter(std::size_t i) const {
    if (i < lights.size()) return *lights[i];
    i -= lights.size();
    return i < surface_lights.size() ? *surface_lights[i] : *environment_light;
  }
  bool is_surface_emitter(std::size_t i) const {
    return i >= lights.size() && i < lights.size() + surface_lights.size();
  }
  Color ambient;     // Ia
  Color background;  // what a ray that leaves the scene returns, without an environment
  std::unique_ptr<Environment> environment;  // environment map (000 §4.1.3), or null
  RenderSettings render;
  DisplaySettings display;
  // The methods' and accelerators' own objects of the file ("whitted", "bvh", ...), read by
  // their registry entries (integrators/method_registry.h, accel/accelerator_registry.h).
  PluginSettings plugin_settings;
  AntialiasingSettings antialiasing;  // the "aa" object
  std::vector<std::string> warnings;

  // Builds the accelerator named in render.accelerator and the derived quantities.
  void prepare();

  bool intersect(const Ray& ray, Intersection& intersection) const {
    return accelerator_->intersect(ray, intersection);
  }
  bool occluded(const Ray& ray) const { return accelerator_->occluded(ray); }
  // Whether a material is a thin sheet that lets light through (Material::thin with kt: a window
  // pane): shadow rays then look for what they cross instead of asking occluded().
  bool has_thin_sheets() const { return thin_sheets_; }
  // Whether any material lets light through (Material::lets_light_through: refraction or
  // transparency); without one, whatever lies on a shadow ray's segment blocks it.
  bool lets_light_through() const { return lets_light_through_; }
  // The first hit along the ray that is not a thin sheet, the sheets before it crossed: `through` is
  // the product of what each lets through at the angle it is crossed (thin_sheet_transmittance,
  // shading/material_bsdf.h); 1 when none is crossed. False, with what crosses in `through`, when
  // the ray leaves the scene (or reaches t_max). More than kMaxSheetsCrossed sheets in a row block
  // the ray.
  bool intersect_past_sheets(Ray ray, Intersection& hit, Color& through) const;
  // What crosses the ray's segment: 1 when nothing lies on it, 0 when something opaque does, else
  // the product of the sheets' transmittances — one visibility for every method's shadow rays
  // (the path tracer's, the direct light of radiosity's first shot, of meshless sites and of the
  // local probe).
  Color transmittance(const Ray& ray) const;
  // What a ray leaving the scene along the unit direction sees: the environment map, or the
  // background color.
  Color background_along(const Vec3& direction) const;
  // What arrives from outside the scene along a direction as light: the environment's radiance,
  // black without one (the background lights nothing).
  Color sky_along(const Vec3& direction) const;

  const Material& material_of(const Intersection& hit) const {
    return materials[primitives[hit.primitive].material];
  }
  const SceneObject& object_of(const Intersection& hit) const {
    return objects[primitives[hit.primitive].object];
  }
  // Bounds of the bounded primitives (planes excluded).
  const Bounds3& bounds() const { return bounds_; }
  // SPEC §8: secondary rays start this far off the surface at p, along the normal, to avoid
  // acne: a part scaled to the scene's extent plus a part relative to |p|, far above double
  // rounding of a hit point there (and above float's, with bvh-fast: its position_error) and
  // far below any feature.
  double ray_offset(const Vec3& p) const {
    return ray_offset_ + offset_per_position_ * std::max({std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)});
  }
  const Accelerator& accelerator() const { return *accelerator_; }
  double accelerator_build_seconds() const { return build_seconds_; }

 private:
  std::unique_ptr<Accelerator> accelerator_;
  Bounds3 bounds_;
  double ray_offset_ = 1e-6;
  double offset_per_position_ = 1e-12;
  double build_seconds_ = 0;
  bool thin_sheets_ = false;
  bool lets_light_through_ = false;
};

}  // namespace candela
