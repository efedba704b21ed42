// Everything a method reads: geometry, materials, lights, camera and settings. Methods never
// edit it (SPEC "Architecture").
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "accel/accelerator.h"
#include "camera/antialiasing.h"
#include "camera/camera.h"
#include "camera/tone_map.h"
#include "radiosity/radiosity_settings.h"  // (until the methods own their settings)
#include "scene/light.h"
#include "shading/material.h"
#include "util/error.h"

namespace candela {

struct RenderSettings {
  std::string method = "whitted";
  SourceLocation method_location;
  uint64_t seed = 0;
  std::string accelerator = "list";
  AcceleratorSettings accelerator_settings;
  double ray_offset = 0;  // 0: derived from the scene's extent (see Scene::ray_offset)
  int tile_size = 16;
};

struct WhittedSettings {
  int max_depth = 5;         // primary rays are depth 0 (000 §5.5)
  double min_weight = 1e-3;  // adaptive depth: stop when the product of the k's is below
  bool shadows = true;
};

struct LocalSettings {
  bool shadows = true;
};

// The raster method (SPEC §9).
enum class RasterShading { flat, gouraud, phong, dot_product };

struct RasterSettings {
  RasterShading shading = RasterShading::phong;
  int segments = 32;           // tessellation: divisions of a full turn
  double crease_angle = 60;    // degrees: sharper edges keep two normals at a vertex
  bool shadows = false;        // shadow rays from the shaded points (through the accelerator)
};

// The meshless method's settings (SPEC §11, seed 002): scene key "meshless".
enum class MeshlessBasisKind { radial, normalized, shepard };
enum class MeshlessKernel { gaussian, cubic };
enum class MeshlessDisplay { global, direct, indirect, hybrid };
enum class MeshlessAreas { integrated, thesis };

struct MeshlessSettings {
  MeshlessBasisKind basis = MeshlessBasisKind::normalized;
  MeshlessKernel kernel = MeshlessKernel::gaussian;  // the radial basis's mother function
  double spacing = 0;     // Δ: no two sites closer (site distance); 0: the scene's size / 50
  int neighbours = 10;    // m: the radius holds the m nearest sites
  int grid = 64;          // camera rays per image side for the first sites
  int rounds = 4;         // rounds of secondary rays
  MeshlessAreas effective_area = MeshlessAreas::integrated;
  double tolerance = 1e-4;     // the iteration stops when no coefficient changes by more (relative)
  int max_iterations = 1000;
  MeshlessDisplay display = MeshlessDisplay::global;
  double shepard_power = 2;
  int max_sites = 50000;       // refused beyond: the transfer matrix grows as n²
};

// The path-traced reference (SPEC §12): scene key "path".
struct PathSettings {
  int spp = 64;         // passes of one sample per pixel; 0: as many as `time` allows
  double time = 0;      // seconds; > 0: stop after the pass that reaches it (or at spp, if set)
  int max_depth = 0;    // bounces at most; 0: unlimited (Russian roulette ends every path)
  int roulette_depth = 3;  // Russian roulette from this bounce on
  double checkpoint_interval = 60;  // seconds between checkpoints (candela render --checkpoint)
};

// One entry of the scene file's "shapes" array.
struct SceneObject {
  std::string name;
  std::string type;
  uint32_t first_primitive = 0;
  uint32_t primitive_count = 0;
};

// One entry of the scene file's "cameras" array: another view of the same scene, chosen with
// `candela render --camera NAME`. The name goes into output file names.
struct NamedCamera {
  std::string name;
  std::unique_ptr<Camera> camera;
};

class Environment;

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
  std::vector<std::unique_ptr<Light>> lights;
  Color ambient;     // Ia
  Color background;  // what a ray that leaves the scene returns, without an environment
  std::unique_ptr<Environment> environment;  // environment map (000 §4.1.3), or null
  RenderSettings render;
  DisplaySettings display;
  WhittedSettings whitted;
  LocalSettings local;
  RasterSettings raster;
  RadiositySettings radiosity;
  MeshlessSettings meshless;
  PathSettings path;
  AntialiasingSettings antialiasing;  // the "aa" object
  std::vector<std::string> warnings;

  // Builds the accelerator named in render.accelerator and the derived quantities.
  void prepare();

  bool intersect(const Ray& ray, Intersection& intersection) const {
    return accelerator_->intersect(ray, intersection);
  }
  bool occluded(const Ray& ray) const { return accelerator_->occluded(ray); }
  // What a ray leaving the scene along the unit direction sees: the environment map, or the
  // background colour.
  Color background_along(const Vec3& direction) const;

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
  // rounding of a hit point there and far below any feature.
  double ray_offset(const Vec3& p) const {
    return ray_offset_ + 1e-12 * std::max({std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)});
  }
  const Accelerator& accelerator() const { return *accelerator_; }
  double accelerator_build_seconds() const { return build_seconds_; }

 private:
  std::unique_ptr<Accelerator> accelerator_;
  Bounds3 bounds_;
  double ray_offset_ = 1e-6;
  double build_seconds_ = 0;
};

}  // namespace candela
