#include "scene/scene_loader.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "accel/accelerator_registry.h"
#include "accel/bounding_volume.h"
#include "camera/antialiasing.h"
#include "camera/pixel_filter.h"
#include "geometry/flipped_shape.h"
#include "geometry/transformed_shape.h"
#include "io/gltf_scene.h"
#include "io/json_node.h"
#include "io/pbrt_scene.h"
#include "scene/camera_registry.h"
#include "scene/environment_registry.h"
#include "scene/json_transform.h"
#include "scene/light_registry.h"
#include "scene/load_context.h"
#include "scene/material_registry.h"
#include "scene/shape_registry.h"
#include "shading/environment.h"
#include "shading/photometric_units.h"
#include "util/file_extension.h"
#include "util/input_file.h"
#include "util/registry.h"

namespace candela {

namespace {

constexpr const char* kFormat = "candela/1";

// A "lights" array: each entry by the light registry; ambient entries add to ambient.
void read_light_list(const JsonNode& lights, Color& ambient, std::vector<std::unique_ptr<Light>>& out,
                     const LoadContext& context) {
  for (std::size_t i = 0; i < lights.size(); ++i) {
    const JsonNode node = lights.element(i);
    node.expect_object();
    const JsonNode type = node.at("type");
    const LightEntry* entry = find_light(type.as_string());
    if (!entry)
      type.fail("unknown light \"" + type.as_string() +
                "\" (expected one of: " + entry_names(light_entries()) + ")");
    auto light = entry->create(node, ambient, context);
    node.allow({"name"});
    node.finish();
    if (light) out.push_back(std::move(light));
  }
}

class SceneReader {
 public:
  SceneReader(const JsonDocument& document, const std::string& base_directory,
              std::span<const SettingsSection> plugin_sections)
      : root_(document, document.root(), ""), plugin_sections_(plugin_sections) {
    context_.base_directory = base_directory;
  }

  std::unique_ptr<Scene> read() {
    auto scene = std::make_unique<Scene>();
    scene_ = scene.get();
    context_.materials = &scene->materials;
    context_.warnings = &scene->warnings;
    context_.named_materials = &named_materials_;
    context_.input_files = &scene->input_files;
    root_.expect_object();
    const JsonNode format = root_.at("format");
    if (format.as_string() != kFormat)
      format.fail(fmt::format("unsupported format \"{}\" (expected \"{}\")", format.as_string(), kFormat));

    scene->camera = read_camera(root_.at("camera"));
    read_named_cameras();
    scene->background = root_.color("background", Color(0), Range::non_negative());
    if (const auto environment = root_.get("environment")) {
      scene->environment = read_environment(*environment, context_);
      if (root_.has("background"))
        scene->warnings.push_back(
            root_.at("background").location().describe() +
            ": background is not used: the environment map gives what rays leaving the scene see");
    }
    scene->ambient = root_.color("ambient", Color(0), Range::non_negative());
    read_settings();
    read_materials();
    read_lights();
    read_shapes();
    spread_luminous_flux();
    make_surface_lights();
    root_.finish();
    scene->prepare();
    return scene;
  }

 private:
  // The "cameras" array: the keys of "camera" plus a name. An absent width or height is the one
  // of "camera" (so --set camera.width=… resizes every view that does not fix its own); every
  // other absent key takes its usual default, as in "camera".
  void read_named_cameras() {
    const auto cameras = root_.get("cameras");
    if (!cameras) return;
    std::map<std::string, std::string> path_of_name;
    for (std::size_t i = 0; i < cameras->size(); ++i) {
      const JsonNode node = cameras->element(i);
      node.expect_object();
      const JsonNode name_node = node.at("name");
      const std::string name = name_node.as_string();
      check_camera_name(name_node, name);
      const auto [previous, inserted] = path_of_name.emplace(name, node.path());
      if (!inserted)
        name_node.fail("duplicate camera name \"" + name + "\" (" + previous->second + " has it already)");
      scene_->cameras.push_back({name, read_camera(node, scene_->camera->width(), scene_->camera->height())});
    }
  }

  // Names go into output file names (out-NAME.png) and are chosen with --camera, where "default"
  // means "camera" and "all" every named camera.
  static void check_camera_name(const JsonNode& node, const std::string& name) {
    if (name.empty()) node.fail("a camera name must not be empty");
    const bool allowed = std::all_of(name.begin(), name.end(), [](char c) {
      return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
             c == '-';
    });
    if (!allowed)
      node.fail("camera name \"" + name +
                "\" may only use letters, digits, '_' and '-' (it becomes part of output file names)");
    if (name == "default" || name == "all")
      node.fail("camera name \"" + name + "\" is reserved (--camera " + name + " means " +
                (name == "default" ? "the \"camera\" object" : "every named camera") + ")");
  }

  void read_settings() {
    if (const auto render = root_.get("render")) {
      scene_->render.method = render->string("method", scene_->render.method);
      if (render->has("method")) scene_->render.method_location = render->at("method").location();
      const double seed = render->number("seed", 0, {0, 9007199254740992.0, false, false});
      scene_->render.seed = static_cast<uint64_t>(seed);
      if (const auto accelerator = render->get("accelerator")) {
        scene_->render.accelerator = accelerator->as_string();
        if (!find_accelerator(scene_->render.accelerator))
          accelerator->fail("unknown accelerator \"" + scene_->render.accelerator +
                            "\" (expected one of: " + entry_names(accelerator_entries()) + ")");
      }
      if (const auto volume = render->get("bounding_volume")) {
        const auto kind = kBoundingVolumeNames.value(volume->as_string());
        if (!kind)
          volume->fail("unknown bounding volume \"" + volume->as_string() +
                       "\" (expected one of: " + kBoundingVolumeNames.names() + ")");
        scene_->render.bounding_volume = *kind;
      }
      scene_->render.ray_offset = render->number("ray_offset", 0.0, Range::non_negative());
      scene_->render.tile_size = render->integer("tile_size", 16, {1, 4096, false, false});
      scene_->render.surface_light_samples = render->integer(
          "surface_light_samples", scene_->render.surface_light_samples, {1, 64, false, false});
      scene_->render.environment_light_samples = render->integer(
          "environment_light_samples", scene_->render.environment_light_samples, {1, 64, false, false});
      scene_->render.memory_limit_mib = render->number("memory_limit_mib", 0.0, Range::non_negative());
      if (render->has("memory_limit_mib"))
        scene_->render.memory_limit_location = render->at("memory_limit_mib").location();
      render->finish();
    }
    if (const auto film = root_.get("film")) {
      scene_->display.out_of_range = film->enumeration("out_of_range", OutOfRange::clamp, kOutOfRangeNames);
      scene_->display.exposure = film->number("exposure", 0.0, {-64, 64, false, false});
      scene_->display.srgb = film->boolean("srgb", true);
      film->finish();
    }
    // Every accelerator's and method's own object, checked now by its reader (the plugin reads
    // it again when it is made): an unknown key or a bad value is refused at load time.
    for (const AcceleratorEntry& entry : accelerator_entries())
      if (const auto node = root_.get(entry.name)) entry.create(*node, scene_->render.bounding_volume);
    for (const SettingsSection& section : plugin_sections_)
      if (const auto node = root_.get(section.key)) section.check(*node);
    if (const auto aa = root_.get("aa")) read_antialiasing(*aa);
  }

  void read_antialiasing(const JsonNode& aa) {
    AntialiasingSettings& settings = scene_->antialiasing;
    aa.expect_object();
    if (const auto mode = aa.get("mode")) {
      const auto value = kAntialiasingModeNames.value(mode->as_string());
      if (!value)
        mode->fail("unknown anti-aliasing mode \"" + mode->as_string() +
                   "\" (expected one of: " + kAntialiasingModeNames.names() + ")");
      settings.mode = *value;
    }
    settings.n = aa.integer("n", settings.n, {1, 64, false, false});
    settings.max_level = aa.integer("max_level", settings.max_level, {0, 8, false, false});
    if (const auto threshold = aa.get("threshold")) {
      if (threshold->json().is_array() && threshold->size() != 3)
        threshold->fail("expected three thresholds [r, g, b] or one number");
      settings.threshold = threshold->as_color(Range::non_negative());
    }
    settings.jitter = aa.boolean("jitter", settings.jitter);
    if (const auto filter = aa.get("filter")) {
      settings.filter = filter->as_string();
      if (!find_pixel_filter(settings.filter))
        filter->fail("unknown filter \"" + settings.filter + "\" (expected one of: " + pixel_filter_names() +
                     ")");
    }
    settings.filter_parameters.radius = aa.number("filter_radius", 0.0, Range::non_negative());
    settings.filter_parameters.sigma = aa.number("filter_sigma", 0.0, Range::non_negative());
    try {
      create_pixel_filter(settings.filter, settings.filter_parameters);
    } catch (const std::invalid_argument& e) {
      aa.fail(e.what());
    }
    aa.finish();
  }

  void read_materials() {
    Material fallback;
    fallback.name = "default";
    scene_->materials.push_back(fallback);
    const auto materials = root_.get("materials");
    if (!materials) return;
    materials->expect_object();
    for (const auto& [name, value] : materials->json().items()) {
      const JsonNode node = materials->at(name);
      Material material = read_material(node, context_);
      material.name = name;
      named_materials_[name] = context_.add_material(std::move(material));
    }
  }

  void read_lights() {
    if (const auto lights = root_.get("lights"))
      read_light_list(*lights, scene_->ambient, scene_->lights, context_);
  }

  uint32_t material_for(const JsonNode& shape) {
    const auto node = shape.get("material");
    if (!node) return 0;
    if (node->json().is_string()) return context_.named_material(*node);
    Material material = read_material(*node, context_);
    material.name = node->path();
    return context_.add_material(std::move(material));
  }

  void read_shapes() {
    const auto shapes = root_.get("shapes");
    if (!shapes) return;
    for (std::size_t i = 0; i < shapes->size(); ++i) {
      const JsonNode node = shapes->element(i);
      node.expect_object();
      const JsonNode type = node.at("type");
      const ShapeEntry* entry = find_shape(type.as_string());
      if (!entry)
        type.fail("unknown shape \"" + type.as_string() +
                  "\" (expected one of: " + entry_names(shape_entries()) + ")");
      SceneObject object;
      object.type = std::string(entry->name);
      object.name = node.string("name", fmt::format("{}#{}", entry->name, i));
      const uint32_t material = material_for(node);
      Transform transform;
      if (const auto transform_node = node.get("transform")) transform = read_transform(*transform_node);
      // Any shape's normals turned the other way (geometry/flipped_shape.h).
      const bool flip_normals = node.boolean("flip_normals", false);
      object.two_sided = node.boolean("two_sided", false);
      ShapeBuild build = entry->create(node, transform, context_);
      node.finish();
      object.first_primitive = static_cast<uint32_t>(scene_->primitives.size());
      object.primitive_count = static_cast<uint32_t>(build.shapes.size());
      const auto object_index = static_cast<uint32_t>(scene_->objects.size());
      for (std::size_t s = 0; s < build.shapes.size(); ++s) {
        std::unique_ptr<Shape> shape = std::move(build.shapes[s]);
        if (!build.transform_applied && !transform.is_identity())
          shape = std::make_unique<TransformedShape>(std::move(shape), transform);
        if (flip_normals) shape = std::make_unique<FlippedShape>(std::move(shape));
        const int own = build.materials[s];
        scene_->primitives.push_back({shape.get(), own >= 0 ? uint32_t(own) : material, object_index});
        scene_->shapes.push_back(std::move(shape));
      }
      scene_->objects.push_back(std::move(object));
      object_locations_.push_back(node.location());
    }
  }

  // A material given in lumens ("emission_luminous_flux") becomes, for each object that
  // uses it, a copy emitting Φ / A (A the object's area of that material) from each side; an
  // object of no area there (an unbounded plane) emits nothing, with a warning.
  void spread_luminous_flux() {
    for (std::size_t index = 0; index < scene_->objects.size(); ++index) {
      const SceneObject& object = scene_->objects[index];
      std::map<uint32_t, double> area_of;  // material → the object's area of it
      for (uint32_t p = object.first_primitive; p < object.first_primitive + object.primitive_count; ++p) {
        const Primitive& primitive = scene_->primitives[p];
        if (scene_->materials[primitive.material].emission_flux > 0)
          area_of[primitive.material] += primitive.shape->area();
      }
      for (const auto& [material, area] : area_of) {
        Material copy = scene_->materials[material];
        if (area > 0 && std::isfinite(area)) {
          copy.emission = radiometric(copy.emission_flux / area, copy.emission_flux_color);
        } else if (context_.warnings) {
          context_.warnings->push_back(fmt::format(
              "{}: \"{}\" has no bounded area of material \"{}\": its emission_luminous_flux lights nothing",
              object_locations_[index].describe(), object.name, copy.name));
        }
        copy.emission_flux = 0;
        const uint32_t own = context_.add_material(std::move(copy));
        for (uint32_t p = object.first_primitive; p < object.first_primitive + object.primitive_count; ++p)
          if (scene_->primitives[p].material == material) scene_->primitives[p].material = own;
      }
    }
  }

  // Every emissive object is a light for the methods that aim shadow rays at emitters
  // (one per object and emissive material). A surface that cannot be sampled (an unbounded
  // plane) lights the scene only where rays happen to hit it (the path tracer's BSDF rays,
  // radiosity's form factors): the methods that need its samples refuse it.
  void make_surface_lights() {
    for (std::size_t index = 0; index < scene_->objects.size(); ++index) {
      const SceneObject& object = scene_->objects[index];
      std::map<uint32_t, std::vector<const Shape*>> shapes_by_material;
      for (uint32_t p = object.first_primitive; p < object.first_primitive + object.primitive_count; ++p) {
        const Primitive& primitive = scene_->primitives[p];
        if (!scene_->materials[primitive.material].emission.is_black())
          shapes_by_material[primitive.material].push_back(primitive.shape);
      }
      for (const auto& [material, shapes] : shapes_by_material) {
        try {
          scene_->surface_lights.push_back(
              std::make_unique<SurfaceLight>(object.name, shapes, scene_->materials[material].emission,
                                             scene_->render.surface_light_samples));
        } catch (const std::invalid_argument&) {
          scene_->unsampled_emitters.push_back({object.name, object.type, object_locations_[index]});
        }
      }
    }
  }

  JsonNode root_;
  std::vector<SourceLocation> object_locations_;  // where each object's entry of "shapes" is
  std::span<const SettingsSection> plugin_sections_;
  Scene* scene_ = nullptr;
  LoadContext context_;
  std::map<std::string, uint32_t> named_materials_;
};

bool is_gltf_path(const std::string& path) {
  const std::string extension = lower_case_extension(path);
  return extension == ".gltf" || extension == ".glb";
}

bool is_pbrt_path(const std::string& path) {
  return lower_case_extension(path) == ".pbrt";
}

std::string no_camera_warning(const std::string& path) {
  return path + ": has no camera: the scene is seen whole from the front, above and to the right";
}

// One glTF file a scene includes, as its "include" names it.
struct Inclusion {
  std::string path;          // resolved against the including file's folder
  std::string file_prefix;   // the folder of "file" as written, for the files the glTF names
  SourceLocation location;   // the include's "file"
  nlohmann::json transform;  // as written (the mesh entry's); null: none
  Eigen::Matrix4d matrix = Eigen::Matrix4d::Identity();
  int scene = -1;
  bool lights = true, cameras = true;
};

std::vector<Inclusion> read_includes(const JsonDocument& document, const std::string& base_directory) {
  std::vector<Inclusion> out;
  const JsonNode root(document, document.root(), "");
  const auto include = root.get("include");
  if (!include) return out;
  std::vector<JsonNode> entries;
  if (include->json().is_array()) {
    for (std::size_t i = 0; i < include->size(); ++i) entries.push_back(include->element(i));
  } else {
    entries.push_back(*include);
  }
  for (const JsonNode& entry : entries) {
    Inclusion inclusion;
    const bool short_form = entry.json().is_string();
    const JsonNode file = short_form ? entry : entry.at("file");
    const std::string written = file.as_string();
    if (!is_gltf_path(written)) file.fail("an include is a glTF file (.gltf or .glb): '" + written + "'");
    const std::filesystem::path as_written(written);
    inclusion.path =
        (as_written.is_absolute() ? as_written : std::filesystem::path(base_directory) / as_written).string();
    const std::filesystem::path folder = as_written.parent_path();
    inclusion.file_prefix = folder.empty() ? "" : (folder / "").string();
    inclusion.location = file.location();
    if (!short_form) {
      entry.expect_object();
      if (const auto transform = entry.get("transform")) {
        inclusion.transform = transform->json();
        inclusion.matrix = read_transform(*transform).matrix();
      }
      inclusion.scene = entry.integer("scene", -1, {0, 1e9, false, false});
      inclusion.lights = entry.boolean("lights", true);
      inclusion.cameras = entry.boolean("cameras", true);
      entry.finish();
    }
    out.push_back(std::move(inclusion));
  }
  return out;
}

// "include": glTF files whose scenes join this one (io/gltf_scene.h), each a file name or
// {"file", "transform", "scene", "lights", "cameras"}, or a list of them. What the including file
// gives wins: its materials by name and its "camera"; the included meshes, lights and named
// cameras come after its own (which keep their located positions). Returns the glTF files'
// warnings.
std::vector<std::string> expand_includes(JsonDocument& document, const std::string& base_directory) {
  std::vector<std::string> warnings;
  const std::vector<Inclusion> inclusions = read_includes(document, base_directory);
  if (inclusions.empty()) return warnings;
  nlohmann::json& root = document.root_to_extend();
  root.erase("include");
  std::set<std::string> camera_names;
  if (root.contains("cameras") && root["cameras"].is_array())
    for (const auto& camera : root["cameras"])
      if (camera.is_object() && camera.contains("name") && camera["name"].is_string())
        camera_names.insert(camera["name"].get<std::string>());
  for (const Inclusion& inclusion : inclusions) {
    GltfSceneDocument included = gltf_scene_document(inclusion.path, inclusion.scene, inclusion.location,
                                                     {inclusion.matrix, inclusion.file_prefix});
    warnings.insert(warnings.end(), included.warnings.begin(), included.warnings.end());
    nlohmann::json& scene = included.document;
    if (scene.contains("materials"))
      for (const auto& [name, material] : scene["materials"].items())
        if (!root["materials"].contains(name)) root["materials"][name] = material;
    if (scene.contains("shapes"))
      for (nlohmann::json shape : scene["shapes"]) {
        if (!inclusion.transform.is_null()) shape["transform"] = inclusion.transform;
        root["shapes"].push_back(std::move(shape));
      }
    if (inclusion.lights && scene.contains("lights"))
      for (const auto& light : scene["lights"]) root["lights"].push_back(light);
    if (!inclusion.cameras) continue;
    // The glTF's cameras, unless the including file has its own "camera" (then they are named
    // views beside it); a name the including file uses already stays its.
    const bool had_camera = root.contains("camera");
    if (!had_camera && scene.contains("camera")) {
      root["camera"] = scene["camera"];
      if (included.framed_camera) warnings.push_back(no_camera_warning(inclusion.path));
    }
    if (scene.contains("cameras"))
      for (const auto& camera : scene["cameras"])
        if (camera_names.insert(camera["name"].get<std::string>()).second) root["cameras"].push_back(camera);
  }
  return warnings;
}

std::unique_ptr<Scene> load_document(std::shared_ptr<JsonDocument> document,
                                     const std::string& base_directory,
                                     const std::vector<std::string>& overrides,
                                     std::span<const SettingsSection> plugin_sections) {
  const std::vector<std::string> included_warnings = expand_includes(*document, base_directory);
  for (const auto& assignment : overrides) document->apply_override(assignment);
  SceneReader reader(*document, base_directory, plugin_sections);
  auto scene = reader.read();
  scene->warnings.insert(scene->warnings.begin(), included_warnings.begin(), included_warnings.end());
  scene->source = document->file();
  scene->plugin_settings = PluginSettings(std::move(document));
  return scene;
}

}  // namespace

std::unique_ptr<Scene> read_scene_text(const std::string& text, const std::string& name,
                                       const std::string& base_directory,
                                       const std::vector<std::string>& overrides,
                                       std::span<const SettingsSection> plugin_sections) {
  auto document = std::make_shared<JsonDocument>(JsonDocument::parse(text, name));
  return load_document(std::move(document), base_directory, overrides, plugin_sections);
}

namespace {

// A glTF file as a scene (io/gltf_scene.h): its document loaded as a scene file's, the overrides
// applied to it but for gltf.scene (which scene of the file), which chooses what is translated.
std::unique_ptr<Scene> read_gltf_scene_file(const std::string& path,
                                            const std::vector<std::string>& overrides,
                                            std::span<const SettingsSection> plugin_sections,
                                            const std::string& directory) {
  int scene = -1;
  std::vector<std::string> rest;
  for (const std::string& assignment : overrides) {
    if (assignment.rfind("gltf.", 0) != 0) {
      rest.push_back(assignment);
      continue;
    }
    const std::size_t equals = assignment.find('=');
    const std::string key = assignment.substr(0, equals);
    const SourceLocation at{"--set " + assignment, 0, 0, key};
    if (key != "gltf.scene") throw InputError(at, "unknown key (a glTF file takes gltf.scene)");
    const std::string value = equals == std::string::npos ? "" : assignment.substr(equals + 1);
    if (value.empty() || value.size() > 9 || value.find_first_not_of("0123456789") != std::string::npos)
      throw InputError(at, "expected the number of one of the file's scenes (0, 1, ...)");
    scene = std::stoi(value);
  }
  GltfSceneDocument translated = gltf_scene_document(path, scene, SourceLocation{path, 0, 0, {}});
  if (translated.framed_camera) translated.warnings.push_back(no_camera_warning(path));
  std::unique_ptr<Scene> loaded =
      read_scene_text(translated.document.dump(2), path, directory, rest, plugin_sections);
  loaded->warnings.insert(loaded->warnings.begin(), translated.warnings.begin(), translated.warnings.end());
  return loaded;
}

// A pbrt-v4 file as a scene (io/pbrt_scene.h): its document loaded as a scene file's, with every
// override; the translation's warnings come first.
std::unique_ptr<Scene> read_pbrt_scene_file(const std::string& path,
                                            const std::vector<std::string>& overrides,
                                            std::span<const SettingsSection> plugin_sections,
                                            const std::string& directory) {
  PbrtSceneDocument translated = pbrt_scene_document(path);
  std::unique_ptr<Scene> loaded =
      read_scene_text(translated.document.dump(2), path, directory, overrides, plugin_sections);
  loaded->warnings.insert(loaded->warnings.begin(), translated.warnings.begin(), translated.warnings.end());
  return loaded;
}

}  // namespace

std::unique_ptr<Scene> read_scene_file(const std::string& path, const std::vector<std::string>& overrides,
                                       std::span<const SettingsSection> plugin_sections) {
  std::string directory = std::filesystem::path(path).parent_path().string();
  if (directory.empty()) directory = ".";
  if (is_gltf_path(path)) return read_gltf_scene_file(path, overrides, plugin_sections, directory);
  if (is_pbrt_path(path)) return read_pbrt_scene_file(path, overrides, plugin_sections, directory);
  // A regular file of bounded size only (a FIFO blocked, /dev/zero exhausted memory).
  const std::string text = read_input_file(path, "the scene file");
  return read_scene_text(text, path, directory, overrides, plugin_sections);
}

std::vector<LightSetup> load_light_setups(const std::string& path) {
  return load_light_setups_text(read_input_file(path, "the light set-ups file"), path);
}

std::vector<LightSetup> load_light_setups_text(const std::string& text, const std::string& name) {
  const JsonDocument document = JsonDocument::parse(text, name);
  const JsonNode root(document, document.root(), "");
  root.expect_object();
  const JsonNode frames = root.at("frames");
  if (frames.size() == 0) frames.fail("needs at least one frame");
  std::vector<LightSetup> setups;
  // A luminaire's file resolves against the set-ups file's folder.
  LoadContext context;
  context.base_directory = std::filesystem::path(name).parent_path();
  if (context.base_directory.empty()) context.base_directory = ".";
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const JsonNode frame = frames.element(i);
    frame.expect_object();
    LightSetup setup;
    setup.name = frame.string("name", "frame" + std::to_string(i));
    if (setup.name.empty() ||
        setup.name.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-") !=
            std::string::npos)
      frame.at("name").fail("must be letters, digits, '_' or '-' (it goes into file names)");
    for (const LightSetup& earlier : setups)
      if (earlier.name == setup.name)
        frame.at("name").fail("\"" + setup.name + "\" names an earlier frame too");
    setup.ambient = frame.color("ambient", Color(0), Range::non_negative());
    context.input_files = &setup.input_files;
    context.warnings = &setup.warnings;
    read_light_list(frame.at("lights"), setup.ambient, setup.lights, context);
    if (const auto materials = frame.get("materials")) {
      materials->expect_object();
      for (const auto& [material, value] : materials->json().items()) {
        const JsonNode edit = materials->at(material);
        edit.expect_object();
        setup.albedo_edits.push_back({material, edit.at("kd").as_color(Range::unit()), edit.location()});
        edit.finish();
      }
    }
    frame.finish();
    setups.push_back(std::move(setup));
  }
  root.finish();
  return setups;
}

std::vector<std::size_t> find_albedo_edit_targets(const Scene& scene, const std::vector<AlbedoEdit>& edits) {
  std::vector<std::size_t> targets;
  for (const AlbedoEdit& edit : edits) {
    const auto found = std::find_if(scene.materials.begin(), scene.materials.end(),
                                    [&](const Material& m) { return m.name == edit.material; });
    if (found == scene.materials.end()) {
      std::string known;
      for (const Material& m : scene.materials)
        if (!m.name.empty() && m.name != "default") known += (known.empty() ? "" : ", ") + m.name;
      throw InputError(edit.location, "the scene has no material \"" + edit.material +
                                          "\" (its named materials: " + (known.empty() ? "none" : known) +
                                          ")");
    }
    targets.push_back(static_cast<std::size_t>(found - scene.materials.begin()));
  }
  return targets;
}

std::unique_ptr<Scene> read_default_scene(const std::vector<std::string>& overrides,
                                          std::span<const SettingsSection> plugin_sections) {
  return read_scene_text(default_scene_text(), "<built-in default scene>", ".", overrides, plugin_sections);
}

}  // namespace candela
