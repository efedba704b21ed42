#include "io/gltf_scene.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <limits>
#include <optional>
#include <set>
#include <string>
#include <utility>

#include "io/gltf_file.h"
#include "math/constants.h"
#include "math/vector.h"

namespace candela {

const std::vector<std::string>& supported_gltf_extensions() {
  static const std::vector<std::string> names = {"KHR_lights_punctual",  "KHR_materials_emissive_strength",
                                                 "KHR_materials_ior",    "KHR_materials_transmission",
                                                 "KHR_materials_volume", "KHR_texture_transform",
                                                 "EXT_lights_ies"};
  return names;
}

namespace {

using Json = nlohmann::json;

// The image size of a glTF camera's view: 640 pixels wide, as high as its aspect ratio makes it.
constexpr int kImageWidth = 640;

// glTF's roughness 0 is a perfect mirror; Candela's microfacet lobes need a width.
constexpr double kLeastRoughness = 1e-3;
// Schlick's F0 stays below 1 (Candela's fresnel_f0 range): a white metal reflects 99.9 %.
constexpr double kGreatestF0 = 0.999;

Json array_of(const Vec3& v) {
  return Json::array({v.x, v.y, v.z});
}
Json array_of(const Color& c) {
  return Json::array({c.r, c.g, c.b});
}

// Reads the file's JSON where the scene needs it, each value checked and located by its JSON path.
class SceneTranslator {
 public:
  SceneTranslator(const GltfFile& file, const GltfPlacement& placement)
      : file_(file), json_(file.json), placement_(placement) {}

  GltfSceneDocument translate(int requested_scene) {
    check_extensions();
    const int scene = gltf_scene_index(file_, requested_scene);
    std::vector<GltfNodePlacement> nodes = gltf_scene_nodes(file_, scene);
    // The includer's placement moves cameras and lights (the mesh entry carries its own transform).
    for (GltfNodePlacement& placed : nodes) placed.world = placement_.matrix * placed.world;
    document_ = {{"format", "candela/1"}};
    read_materials();
    add_meshes(nodes, scene);
    add_cameras(nodes);
    add_lights(nodes);
    return {std::move(document_), std::move(warnings_), framed_camera_};
  }

 private:
  [[noreturn]] void fail(const std::string& path, const std::string& message) const {
    file_.fail(fmt::format("{}: {}", path, message));
  }
  void warn(const std::string& message) { warnings_.push_back(file_.path + ": " + message); }

  // --- checked values -------------------------------------------------------------------------

  static const Json* find(const Json& object, const char* key) {
    if (!object.is_object()) return nullptr;
    const auto found = object.find(key);
    return found == object.end() ? nullptr : &*found;
  }
  const Json& object_at(const Json& object, const char* key, const std::string& path) const {
    static const Json empty = Json::object();
    const Json* value = find(object, key);
    if (!value) return empty;
    if (!value->is_object()) fail(path + "." + key, "must be an object");
    return *value;
  }
  double number(const Json& object, const char* key, double fallback, const std::string& path, double least,
                double most) const {
    const Json* value = find(object, key);
    if (!value) return fallback;
    if (!value->is_number() || !std::isfinite(value->get<double>()))
      fail(path + "." + key, "must be a finite number");
    const double x = value->get<double>();
    if (x < least || x > most)
      fail(path + "." + key, fmt::format("must lie in [{}, {}] (found {})", least, most, x));
    return x;
  }
  std::vector<double> numbers(const Json& object, const char* key, std::vector<double> fallback,
                              const std::string& path, double least, double most) const {
    const Json* value = find(object, key);
    if (!value) return fallback;
    if (!value->is_array() || value->size() != fallback.size())
      fail(path + "." + key, fmt::format("must be an array of {} numbers", fallback.size()));
    std::vector<double> out;
    for (std::size_t k = 0; k < value->size(); ++k) {
      const Json& x = (*value)[k];
      if (!x.is_number() || !std::isfinite(x.get<double>()) || x.get<double>() < least ||
          x.get<double>() > most)
        fail(fmt::format("{}.{}[{}]", path, key, k),
             fmt::format("must be a number in [{}, {}]", least, most));
      out.push_back(x.get<double>());
    }
    return out;
  }
  int index(const Json& object, const char* key, std::size_t count, const std::string& path) const {
    const Json* value = find(object, key);
    if (!value) return -1;
    if (!value->is_number_unsigned() || value->get<std::size_t>() >= count)
      fail(path + "." + key, fmt::format("must be the index of one of {} element(s)", count));
    return value->get<int>();
  }
  const Json& element(const char* array, std::size_t i) const { return json_.at(array).at(i); }
  std::size_t count(const char* array) const {
    const Json* value = find(json_, array);
    return value && value->is_array() ? value->size() : 0;
  }

  // The file an image or IES profile object names by its "uri", which must exist beside the glTF
  // file (fails at PATH.uri); none when it is embedded (a data URI or a bufferView).
  std::optional<std::string> external_file(const Json& object, const std::string& path) const {
    const Json* uri = find(object, "uri");
    if (!uri || !uri->is_string() || uri->get<std::string>().rfind("data:", 0) == 0) return std::nullopt;
    const std::string file = uri->get<std::string>();
    std::error_code error;
    if (!std::filesystem::is_regular_file(std::filesystem::path(file_.path).parent_path() / file, error))
      fail(path + ".uri", fmt::format("'{}' is not a file (relative to the glTF file)", file));
    return file;
  }

  // --- extensions -----------------------------------------------------------------------------

  void check_extensions() {
    const auto& supported = supported_gltf_extensions();
    const auto is_supported = [&](const std::string& name) {
      return std::find(supported.begin(), supported.end(), name) != supported.end();
    };
    for (const std::string& name : file_.model.extensionsRequired)
      if (!is_supported(name))
        fail("extensionsRequired",
             fmt::format("Candela does not support the extension \"{}\" the file requires (supported: {})",
                         name, fmt::join(supported, ", ")));
    for (const std::string& name : file_.model.extensionsUsed)
      if (!is_supported(name))
        warn(fmt::format("extension \"{}\" is not supported: what it adds is ignored", name));
  }

  // --- materials ------------------------------------------------------------------------------

  // Unique names: the glTF name where it has one, else "material-N".
  void read_materials() {
    std::set<std::string> taken;
    Json materials = Json::object();
    for (std::size_t i = 0; i < count("materials"); ++i) {
      const Json& material = element("materials", i);
      std::string name = material.is_object() && material.contains("name") && material["name"].is_string()
                             ? material["name"].get<std::string>()
                             : "";
      if (name.empty()) name = fmt::format("material-{}", i);
      if (taken.count(name)) name = fmt::format("{}#{}", name, i);
      taken.insert(name);
      material_names_.push_back(name);
      materials[name] = material_of(material, fmt::format("materials[{}]", i));
    }
    document_["materials"] = std::move(materials);
  }

  // The image texture of a textureInfo (the base colour's): its file, sRGB, times multiplier.
  Json image_texture(const Json& info, const std::string& path, const Color& multiplier) {
    const int texture = index(info, "index", count("textures"), path);
    if (texture < 0) fail(path + ".index", "is required");
    const std::string texture_path = fmt::format("textures[{}]", texture);
    const Json& texture_object = element("textures", std::size_t(texture));
    const int image = index(texture_object, "source", count("images"), texture_path);
    if (image < 0) return nullptr;
    const Json& image_object = element("images", std::size_t(image));
    const std::optional<std::string> file = external_file(image_object, fmt::format("images[{}]", image));
    if (!file) {
      warn(fmt::format("{}: image {} is embedded in the file (not supported yet): the factor alone is used",
                       path, image));
      return nullptr;
    }
    Json out = {{"type", "image"},
                {"file", placement_.file_prefix + *file},
                {"encoding", "srgb"},
                {"multiplier", array_of(multiplier)}};
    // The sampler's wrap mode (S; T alike in every exporter we know).
    const int sampler = index(texture_object, "sampler", count("samplers"), texture_path);
    if (sampler >= 0) {
      const double wrap = number(element("samplers", std::size_t(sampler)), "wrapS", 10497,
                                 fmt::format("samplers[{}]", sampler), 0, 1e9);
      out["wrap"] = wrap == 33071 ? "clamp" : wrap == 33648 ? "mirror" : "repeat";
    }
    if (index(info, "texCoord", 8, path) > 0)
      warn(path + ": a second texture coordinate set is not supported: TEXCOORD_0 is used");
    // KHR_texture_transform in glTF's (u, v), v down the image; Candela's v runs up (v_c = 1 − v):
    // u' = sx u + ox, v_c' = sy v_c + (1 − sy − oy).
    const Json& extensions = object_at(info, "extensions", path);
    if (const Json* transform = find(extensions, "KHR_texture_transform")) {
      const std::string at = path + ".extensions.KHR_texture_transform";
      const auto offset = numbers(*transform, "offset", {0, 0}, at, -1e9, 1e9);
      const auto scale = numbers(*transform, "scale", {1, 1}, at, -1e9, 1e9);
      if (number(*transform, "rotation", 0, at, -1e9, 1e9) != 0)
        warn(at + ": rotation is not supported: offset and scale alone are used");
      out["mapping"] = {{"type", "uv"},
                        {"scale", Json::array({scale[0], scale[1]})},
                        {"offset", Json::array({offset[0], 1 - scale[1] - offset[1]})}};
    }
    return out;
  }

  Json material_of(const Json& material, const std::string& path) {
    if (!material.is_object()) fail(path, "must be an object");
    const Json& pbr = object_at(material, "pbrMetallicRoughness", path);
    const std::string pbr_path = path + ".pbrMetallicRoughness";
    const auto base_rgba = numbers(pbr, "baseColorFactor", {1, 1, 1, 1}, pbr_path, 0, 1);
    const Color base(base_rgba[0], base_rgba[1], base_rgba[2]);
    const double metallic = number(pbr, "metallicFactor", 1, pbr_path, 0, 1);
    const double roughness = number(pbr, "roughnessFactor", 1, pbr_path, 0, 1);
    const Json& extensions = object_at(material, "extensions", path);
    const std::string extensions_path = path + ".extensions";
    const Json& transmission_object = object_at(extensions, "KHR_materials_transmission", extensions_path);
    const double transmission = number(transmission_object, "transmissionFactor", 0,
                                       extensions_path + ".KHR_materials_transmission", 0, 1);
    const double ior = number(object_at(extensions, "KHR_materials_ior", extensions_path), "ior", 1.5,
                              extensions_path + ".KHR_materials_ior", 1, 10);
    const double dielectric_f0 = (ior - 1) * (ior - 1) / ((ior + 1) * (ior + 1));
    const double diffuse_share = (1 - metallic) * (1 - transmission);
    const double transmitted = (1 - metallic) * transmission;
    // glTF's BRDF: the diffuse beneath the facets' Fresnel reflection ("layered": the path tracer
    // gives the diffuse 1 − F(N·V) and leaves the facets out of its energy rule); the transmitted
    // part's reflection is its dielectric lobe's, so the facets cover what is not transmitted.
    const Color diffuse = base * diffuse_share;
    const Color f0 = Color(dielectric_f0 * (1 - metallic)) + base * metallic;
    Json out = {{"type", "cook-torrance"}, {"microfacet", "ggx"},
                {"layered", true},         {"roughness", std::max(roughness * roughness, kLeastRoughness)},
                {"ks", 1 - transmitted},   {"fresnel_f0", array_of(min(f0, Color(kGreatestF0)))}};
    out["kd"] = array_of(diffuse);
    if (const Json* texture = find(pbr, "baseColorTexture"); texture && diffuse_share > 0) {
      Json image = image_texture(*texture, pbr_path + ".baseColorTexture", base * diffuse_share);
      if (!image.is_null()) out["kd"] = std::move(image);
    }
    if (find(pbr, "metallicRoughnessTexture"))
      warn(pbr_path +
           ".metallicRoughnessTexture: not supported yet: metallicFactor and roughnessFactor are used");
    if (find(material, "normalTexture")) warn(path + ".normalTexture: normal maps are not supported yet");
    if (transmitted > 0) {
      out["kt"] = transmitted;
      out["ior"] = ior;
      const Json& volume = object_at(extensions, "KHR_materials_volume", extensions_path);
      const std::string volume_path = extensions_path + ".KHR_materials_volume";
      const double thickness = number(volume, "thicknessFactor", 0, volume_path, 0, 1e16);
      if (thickness == 0) {
        out["thin"] = true;  // glTF's transmission without a volume is a thin wall
      } else {
        const double distance = number(volume, "attenuationDistance", std::numeric_limits<double>::infinity(),
                                       volume_path, 1e-16, 1e16);
        const auto color = numbers(volume, "attenuationColor", {1, 1, 1}, volume_path, 0, 1);
        // Beer's law: T = c^(x/d), σ = −ln c / d per channel (c = 0 held at 1e-6).
        if (std::isfinite(distance)) {
          Color absorption;
          for (int k = 0; k < 3; ++k)
            absorption[k] = -std::log(std::max(color[std::size_t(k)], 1e-6)) / distance;
          out["absorption"] = array_of(absorption);
        }
      }
    }
    // Emission: emissiveFactor × emissiveStrength is a luminance in cd/m² (glTF 2.0, "emissive").
    const auto emissive = numbers(material, "emissiveFactor", {0, 0, 0}, path, 0, 1);
    const double strength =
        number(object_at(extensions, "KHR_materials_emissive_strength", extensions_path), "emissiveStrength",
               1, extensions_path + ".KHR_materials_emissive_strength", 0, 1e16);
    const Color emitted = Color(emissive[0], emissive[1], emissive[2]) * strength;
    if (luminance(emitted) > 0) {
      out["emission_luminance"] = luminance(emitted);
      out["emission_color"] = array_of(emitted);
    }
    if (find(material, "emissiveTexture"))
      warn(path + ".emissiveTexture: not supported yet: emissiveFactor is used");
    // Alpha: BLEND sees through by 1 − alpha; MASK drops the whole material below its cutoff.
    const Json* mode = find(material, "alphaMode");
    const std::string alpha_mode = mode && mode->is_string() ? mode->get<std::string>() : "OPAQUE";
    const double alpha = base_rgba[3];
    if (alpha_mode == "BLEND" && alpha < 1) {
      out["transparency"] = {{"model", "constant"}, {"t", 1 - alpha}};
    } else if (alpha_mode == "MASK") {
      if (alpha < number(material, "alphaCutoff", 0.5, path, 0, 1e16))
        out["transparency"] = {{"model", "constant"}, {"t", 1.0}};
      if (find(pbr, "baseColorTexture"))
        warn(path + ": alphaMode MASK of a texture's alpha is not supported yet");
    }
    return out;
  }

  // --- meshes ---------------------------------------------------------------------------------

  // One mesh entry for the whole scene: io/gltf_import.h reads its primitives, each with the scene
  // material its glTF material became (the default material where it has none).
  void add_meshes(const std::vector<GltfNodePlacement>& nodes, int scene) {
    std::vector<int> meshes;
    if (scene < 0) {
      for (std::size_t m = 0; m < file_.model.meshes.size(); ++m) meshes.push_back(int(m));
    } else {
      for (const GltfNodePlacement& placed : nodes)
        if (const int mesh = file_.model.nodes[std::size_t(placed.node)].mesh; mesh >= 0)
          meshes.push_back(mesh);
    }
    if (meshes.empty()) return;
    bool every_normal = true, any_without_material = false;
    for (const int mesh : meshes) {
      if (mesh >= static_cast<int>(file_.model.meshes.size())) continue;  // the mesh reader names it
      for (const tinygltf::Primitive& primitive : file_.model.meshes[std::size_t(mesh)].primitives) {
        if (primitive.mode != TINYGLTF_MODE_TRIANGLES) continue;
        every_normal = every_normal && primitive.attributes.count("NORMAL") > 0;
        any_without_material = any_without_material || primitive.material < 0;
      }
    }
    Json shape = {{"type", "mesh"},
                  {"name", std::filesystem::path(file_.path).stem().string()},
                  {"file", placement_.file_prefix + std::filesystem::path(file_.path).filename().string()},
                  {"normals", every_normal ? "file" : "flat"},
                  {"file_materials", material_names_}};
    if (scene >= 0) shape["scene"] = scene;
    if (any_without_material) {
      // glTF 2.0: a primitive without a material has the default one, every factor at its default.
      document_["materials"]["glTF default"] = material_of(Json::object(), "the default material");
      shape["material"] = "glTF default";
    }
    document_["shapes"] = Json::array({shape});
  }

  // --- cameras --------------------------------------------------------------------------------

  static Vec3 point_of(const Eigen::Matrix4d& world, double x, double y, double z) {
    const Eigen::Vector4d p = world * Eigen::Vector4d(x, y, z, 1);
    return {p.x(), p.y(), p.z()};
  }
  static Vec3 direction_of(const Eigen::Matrix4d& world, double x, double y, double z) {
    const Eigen::Vector4d d = world * Eigen::Vector4d(x, y, z, 0);
    return {d.x(), d.y(), d.z()};
  }

  // A camera name for output files and --camera: letters, digits, '_' and '-', unique.
  std::string camera_name(std::string name, std::size_t index) {
    for (char& c : name)
      if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_' && c != '-') c = '_';
    if (name.empty() || name == "default" || name == "all") name = fmt::format("camera-{}", index);
    while (camera_names_.count(name)) name += fmt::format("-{}", index);
    camera_names_.insert(name);
    return name;
  }

  void add_cameras(const std::vector<GltfNodePlacement>& nodes) {
    Json cameras = Json::array();
    for (const GltfNodePlacement& placed : nodes) {
      const int camera = file_.model.nodes[std::size_t(placed.node)].camera;
      if (camera < 0) continue;
      const std::string path = fmt::format("cameras[{}]", camera);
      if (camera >= static_cast<int>(count("cameras")))
        fail(fmt::format("nodes[{}].camera", placed.node), "names a camera that does not exist");
      const Json& object = element("cameras", std::size_t(camera));
      // The lens looks down the node's −Z, its top along +Y (the view ignores scale).
      const Vec3 eye = point_of(placed.world, 0, 0, 0);
      const Vec3 forward = direction_of(placed.world, 0, 0, -1);
      const Vec3 up = direction_of(placed.world, 0, 1, 0);
      if (!(length(cross(forward, up)) > 0))
        fail(fmt::format("nodes[{}]", placed.node), "the camera's transform has no view direction");
      Json view = {{"eye", array_of(eye)},
                   {"target", array_of(eye + normalize(forward))},
                   {"up", array_of(normalize(up))}};
      double aspect = 4.0 / 3.0;
      const Json* type = find(object, "type");
      if (type && *type == "orthographic") {
        const Json& orthographic = object_at(object, "orthographic", path);
        const double xmag = std::fabs(number(orthographic, "xmag", 1, path + ".orthographic", -1e16, 1e16));
        const double ymag = std::fabs(number(orthographic, "ymag", 1, path + ".orthographic", -1e16, 1e16));
        if (xmag == 0 || ymag == 0) fail(path + ".orthographic", "xmag and ymag must not be 0");
        view["type"] = "orthographic";
        view["window"] = Json::array({-xmag, xmag, -ymag, ymag});
        aspect = xmag / ymag;
      } else if (type && *type == "perspective") {
        const Json& perspective = object_at(object, "perspective", path);
        const double yfov = number(perspective, "yfov", 0.8, path + ".perspective", 1e-6, kPi - 1e-6);
        view["vertical_fov"] = yfov * 180 / kPi;
        aspect = number(perspective, "aspectRatio", aspect, path + ".perspective", 1e-3, 1e3);
      } else {
        fail(path + ".type", "must be \"perspective\" or \"orthographic\"");
      }
      const int height = std::max(1, static_cast<int>(std::lround(kImageWidth / aspect)));
      const Json* name = find(object, "name");
      view["name"] = camera_name(name && name->is_string() ? name->get<std::string>() : "", cameras.size());
      if (cameras.empty()) {
        Json first = view;
        first.erase("name");
        first["width"] = kImageWidth;
        first["height"] = height;
        document_["camera"] = first;
        first_height_ = height;
      } else if (height != first_height_) {
        view["width"] = kImageWidth;
        view["height"] = height;
      }
      cameras.push_back(std::move(view));
    }
    if (cameras.empty()) {
      add_default_camera(nodes);
      return;
    }
    document_["cameras"] = std::move(cameras);
  }

  // No camera in the file: the whole scene seen from the front, above and to the right, as a
  // viewer's "frame all" does (the bounds of the POSITION accessors, which glTF requires).
  void add_default_camera(const std::vector<GltfNodePlacement>& nodes) {
    Vec3 lower(kInfinity, kInfinity, kInfinity), upper(-kInfinity, -kInfinity, -kInfinity);
    for (const GltfNodePlacement& placed : nodes) {
      const int mesh = file_.model.nodes[std::size_t(placed.node)].mesh;
      if (mesh < 0 || mesh >= static_cast<int>(file_.model.meshes.size())) continue;
      for (const tinygltf::Primitive& primitive : file_.model.meshes[std::size_t(mesh)].primitives) {
        const auto position = primitive.attributes.find("POSITION");
        if (position == primitive.attributes.end() || position->second < 0 ||
            position->second >= static_cast<int>(file_.model.accessors.size()))
          continue;
        const tinygltf::Accessor& accessor = file_.model.accessors[std::size_t(position->second)];
        if (accessor.minValues.size() != 3 || accessor.maxValues.size() != 3) continue;
        for (int corner = 0; corner < 8; ++corner) {
          const Vec3 p = point_of(placed.world, corner & 1 ? accessor.maxValues[0] : accessor.minValues[0],
                                  corner & 2 ? accessor.maxValues[1] : accessor.minValues[1],
                                  corner & 4 ? accessor.maxValues[2] : accessor.minValues[2]);
          lower = min(lower, p);
          upper = max(upper, p);
        }
      }
    }
    if (!(lower.x <= upper.x)) lower = upper = Vec3(0, 0, 0);
    const Vec3 center = (lower + upper) * 0.5;
    const double radius = std::max(length(upper - lower) * 0.5, 1e-3);
    constexpr double kVerticalFov = 40;
    const double distance = 1.1 * radius / std::sin(kVerticalFov / 2 * kPi / 180);
    document_["camera"] = {{"eye", array_of(center + normalize(Vec3(0.5, 0.4, 1)) * distance)},
                           {"target", array_of(center)},
                           {"vertical_fov", kVerticalFov},
                           {"width", kImageWidth},
                           {"height", kImageWidth * 3 / 4}};
    framed_camera_ = true;
  }

  // --- lights ---------------------------------------------------------------------------------

  void add_lights(const std::vector<GltfNodePlacement>& nodes) {
    Json lights = Json::array();
    const Json& extensions = object_at(json_, "extensions", "");
    const Json& punctual = object_at(extensions, "KHR_lights_punctual", "extensions");
    const Json* punctual_lights = find(punctual, "lights");
    const Json& ies = object_at(extensions, "EXT_lights_ies", "extensions");
    const Json* ies_profiles = find(ies, "lights");
    bool range_warned = false;
    for (const GltfNodePlacement& placed : nodes) {
      const std::string node_path = fmt::format("nodes[{}].extensions", placed.node);
      const Json& node_extensions = object_at(element("nodes", std::size_t(placed.node)), "extensions",
                                              fmt::format("nodes[{}]", placed.node));
      const Vec3 position = point_of(placed.world, 0, 0, 0);
      // Lights shine down the node's −Z (its scale does not change them).
      const Vec3 aim = direction_of(placed.world, 0, 0, -1);
      if (const Json* use = find(node_extensions, "KHR_lights_punctual")) {
        const std::size_t available =
            punctual_lights && punctual_lights->is_array() ? punctual_lights->size() : 0;
        const int light = index(*use, "light", available, node_path + ".KHR_lights_punctual");
        if (light < 0) fail(node_path + ".KHR_lights_punctual.light", "is required");
        const Json& object = (*punctual_lights)[std::size_t(light)];
        const std::string path = fmt::format("extensions.KHR_lights_punctual.lights[{}]", light);
        if (find(object, "range") && !range_warned) {
          warn(path + ".range: lights reach every distance (inverse square), the range is ignored");
          range_warned = true;
        }
        Json out = punctual_light(object, path, position, aim, placed.node);
        if (!out.is_null()) lights.push_back(std::move(out));
      }
      if (const Json* use = find(node_extensions, "EXT_lights_ies")) {
        const std::size_t available = ies_profiles && ies_profiles->is_array() ? ies_profiles->size() : 0;
        const int light = index(*use, "light", available, node_path + ".EXT_lights_ies");
        if (light < 0) fail(node_path + ".EXT_lights_ies.light", "is required");
        Json out = ies_light(*use, (*ies_profiles)[std::size_t(light)], node_path + ".EXT_lights_ies",
                             fmt::format("extensions.EXT_lights_ies.lights[{}]", light), position, aim,
                             direction_of(placed.world, 1, 0, 0));
        if (!out.is_null()) lights.push_back(std::move(out));
      }
    }
    if (!lights.empty()) document_["lights"] = std::move(lights);
  }

  // KHR_lights_punctual: intensity in candela (point, spot) or lux (directional) of white light,
  // times the colour: its luminance scales the amount, its chromaticity is the light's colour.
  Json punctual_light(const Json& object, const std::string& path, const Vec3& position, const Vec3& aim,
                      int node) {
    const auto rgb = numbers(object, "color", {1, 1, 1}, path, 0, 1);
    const Color color(rgb[0], rgb[1], rgb[2]);
    const double amount = number(object, "intensity", 1, path, 0, 1e16) * luminance(color);
    const Json* type = find(object, "type");
    const std::string kind = type && type->is_string() ? type->get<std::string>() : "";
    if (kind != "point" && kind != "spot" && kind != "directional")
      fail(path + ".type", "must be \"point\", \"spot\" or \"directional\"");
    if (amount == 0) {
      warn(fmt::format("{}: a light of no intensity (node {}) is left out", path, node));
      return nullptr;
    }
    if (!(length(aim) > 0)) fail(fmt::format("nodes[{}]", node), "the light's transform has no direction");
    Json out = {{"color", array_of(color)}};
    if (kind == "directional") {
      out["type"] = "directional";
      out["direction"] = array_of(normalize(aim));
      out["illuminance"] = amount;
      return out;
    }
    out["type"] = kind;
    out["position"] = array_of(position);
    out["luminous_intensity"] = amount;
    if (kind == "spot") {
      // Full inside the inner cone, a smooth step to nothing at the outer one.
      const Json& spot = object_at(object, "spot", path);
      const double outer = number(spot, "outerConeAngle", kPi / 4, path + ".spot", 1e-6, kPi / 2);
      const double inner = number(spot, "innerConeAngle", 0, path + ".spot", 0, outer);
      out["target"] = array_of(position + normalize(aim));
      out["cutoff"] = outer * 180 / kPi;
      out["falloff_start"] = inner * 180 / kPi;
    }
    return out;
  }

  // EXT_lights_ies: the profile's nadir (vertical angle 0) down the node's −Z, its C0 plane the
  // node's X/Z plane (C0 along +X), the candela values × multiplier × the colour's luminance.
  Json ies_light(const Json& use, const Json& profile, const std::string& use_path, const std::string& path,
                 const Vec3& position, const Vec3& aim, const Vec3& c0) {
    const std::optional<std::string> file = external_file(profile, path);
    if (!file) {
      warn(path + ": a profile embedded in the file is not supported yet: the light is left out");
      return nullptr;
    }
    const auto rgb = numbers(use, "color", {1, 1, 1}, use_path, 0, 1);
    const Color color(rgb[0], rgb[1], rgb[2]);
    const double multiplier = number(use, "multiplier", 1, use_path, 0, 1e16) * luminance(color);
    if (multiplier == 0) return nullptr;
    return {{"type", "luminaire"},
            {"file", placement_.file_prefix + *file},
            {"position", array_of(position)},
            {"target", array_of(position + normalize(aim))},
            {"c0", array_of(normalize(c0))},
            {"multiplier", multiplier},
            {"color", array_of(color)}};
  }

  const GltfFile& file_;
  const Json& json_;
  const GltfPlacement& placement_;
  Json document_;
  std::vector<std::string> warnings_;
  std::vector<std::string> material_names_;
  std::set<std::string> camera_names_;
  int first_height_ = 0;
  bool framed_camera_ = false;
};

}  // namespace

GltfSceneDocument gltf_scene_document(const std::string& path, int scene,
                                      const SourceLocation& referenced_from, const GltfPlacement& placement) {
  const GltfFile file = read_gltf_file(path, referenced_from);
  GltfSceneDocument out = SceneTranslator(file, placement).translate(scene);
  // tinygltf's own warnings come with the mesh entry's reading of the file, where it has one.
  if (!out.document.contains("shapes"))
    out.warnings.insert(out.warnings.begin(), file.warnings.begin(), file.warnings.end());
  return out;
}

}  // namespace candela
