// glTF 2.0 files as whole scenes (io/gltf_scene.h): their lights give the lux glTF's units say,
// their cameras stand where their nodes put them, their materials become the documented
// Cook-Torrance parameters per primitive, and what Candela cannot do is an error or a warning.
#include "io/gltf_scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "camera/camera.h"
#include "integrators/probe.h"
#include "integrators/scene_loading.h"
#include "io/mesh_test_files.h"
#include "math/constants.h"
#include "render_support.h"
#include "scene/scene.h"
#include "scratch_directory.h"
#include "shading/photometric_units.h"

namespace candela {
namespace {

using Json = nlohmann::json;

// A 4 × 4 m floor at y = 0 facing up (normals given), two triangles of material 0, as glTF.
Json floor_gltf() {
  std::string bytes;
  const float corners[4][3] = {{-2, 0, -2}, {2, 0, -2}, {2, 0, 2}, {-2, 0, 2}};
  for (const auto& c : corners)
    for (float v : c) testing::put<float>(bytes, v);
  for (int k = 0; k < 4; ++k)
    for (float v : {0.0f, 1.0f, 0.0f}) testing::put<float>(bytes, v);
  for (std::uint16_t i : {0, 2, 1, 0, 3, 2}) testing::put<std::uint16_t>(bytes, i);
  Json file = Json::parse(R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
    "nodes": [{"mesh": 0}],
    "materials": [{"name": "floor", "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1],
                   "metallicFactor": 0, "roughnessFactor": 1}}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2, "material": 0}]}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48},
                    {"buffer": 0, "byteOffset": 48, "byteLength": 48},
                    {"buffer": 0, "byteOffset": 96, "byteLength": 12}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
                   "min": [-2, 0, -2], "max": [2, 0, 2]},
                  {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"},
                  {"bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR"}]})");
  file["buffers"] = Json::array({{{"byteLength", bytes.size()}, {"uri", testing::data_uri(bytes)}}});
  return file;
}

class GltfScene : public ::testing::Test {
 protected:
  // floor_gltf() with a light node (KHR_lights_punctual light 0) at `translation`, rotated by
  // `rotation` (a quaternion), and the file's extensions and lights as given.
  static Json with_light(const Json& light, const std::vector<double>& translation,
                         const std::vector<double>& rotation = {0, 0, 0, 1}) {
    Json file = floor_gltf();
    file["nodes"].push_back({{"translation", translation},
                             {"rotation", rotation},
                             {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
    file["scenes"][0]["nodes"].push_back(1);
    file["extensionsUsed"] = {"KHR_lights_punctual"};
    file["extensions"] = {{"KHR_lights_punctual", {{"lights", Json::array({light})}}}};
    return file;
  }
  std::string write(const Json& file, const std::string& name = "scene.gltf") {
    const std::string path = (directory_.path() / name).string();
    std::ofstream(path) << file.dump(1);
    return path;
  }
  std::unique_ptr<Scene> load(const Json& file, const std::vector<std::string>& overrides = {}) {
    return load_scene_file(write(file), overrides);
  }
  // The local model's irradiance at floor points (x, 0, z) facing up, in lux (its samples are exact).
  static std::vector<double> lux_at(const Scene& scene, const std::vector<std::pair<double, double>>& xz) {
    std::vector<ProbePoint> points;
    for (const auto& [x, z] : xz) points.push_back({{x, 0, z}, {0, 1, 0}});
    ProbeSettings settings;
    settings.method = "local";
    std::vector<double> lux;
    for (const ProbeResult& result : probe(scene, points, settings))
      lux.push_back(kLuminousEfficacy * luminance(result.irradiance));
    return lux;
  }
  std::string error_of(const Json& file, const std::vector<std::string>& overrides = {}) {
    try {
      load(file, overrides);
    } catch (const InputError& e) {
      return e.what();
    }
    ADD_FAILURE() << "no error";
    return "";
  }
  testing::ScratchDirectory directory_{"candela-gltf-scene"};
};

TEST_F(GltfScene, PointAndSpotLightsGiveTheirCandelasAsLux) {
  // 100 cd of white light 2 m above the floor: E = I cos θ / d².
  const auto point = load(with_light({{"type", "point"}, {"intensity", 100}}, {0, 2, 0}));
  const auto lux = lux_at(*point, {{0, 0}, {1, 0}});
  EXPECT_NEAR(lux[0], 25, 1e-9);
  EXPECT_NEAR(lux[1], 100 * (2 / std::sqrt(5.0)) / 5, 1e-9);
  // A coloured light: glTF's intensity is that of white light, times the colour.
  const auto red =
      load(with_light({{"type", "point"}, {"intensity", 100}, {"color", {1, 0.5, 0.25}}}, {0, 2, 0}));
  EXPECT_NEAR(lux_at(*red, {{0, 0}})[0], 25 * luminance(Color(1, 0.5, 0.25)), 1e-9);
  // A spot aimed down (the node's −Z turned to −Y: a −90° turn about x): full inside the inner
  // cone (20°), nothing beyond the outer (40°).
  const double s = std::sin(-kPi / 4), c = std::cos(-kPi / 4);
  const auto spot =
      load(with_light({{"type", "spot"},
                       {"intensity", 100},
                       {"spot", {{"innerConeAngle", 20 * kPi / 180}, {"outerConeAngle", 40 * kPi / 180}}}},
                      {0, 2, 0}, {s, 0, 0, c}));
  const auto cone =
      lux_at(*spot, {{0, 0}, {2 * std::tan(10 * kPi / 180), 0}, {2 * std::tan(45 * kPi / 180), 0}});
  EXPECT_NEAR(cone[0], 25, 1e-9);
  const double at_10 = 2 / std::cos(10 * kPi / 180);
  EXPECT_NEAR(cone[1], 100 * std::cos(10 * kPi / 180) / (at_10 * at_10), 1e-9);
  EXPECT_EQ(cone[2], 0);
}

TEST_F(GltfScene, DirectionalLightGivesItsLuxAlongTheNodesMinusZ) {
  // 1,000 lx down −Z turned 60° about x: light travelling 60° below the horizontal, 30° from the
  // vertical, gives the floor E = 1000 cos 30°.
  const double half_angle = -60 * kPi / 180 / 2;
  const auto scene = load(with_light({{"type", "directional"}, {"intensity", 1000}}, {0, 5, 0},
                                     {std::sin(half_angle), 0, 0, std::cos(half_angle)}));
  EXPECT_NEAR(lux_at(*scene, {{0.5, 0.5}})[0], 1000 * std::cos(30 * kPi / 180), 1e-9);
}

TEST_F(GltfScene, CamerasStandWhereTheirNodesPutThemAndKeepTheirVerticalField) {
  Json file = floor_gltf();
  // Camera 0 at (0, 3, 3) turned 45° down; camera 1 orthographic, straight down.
  const double s = std::sin(-kPi / 8), c = std::cos(-kPi / 8);
  file["nodes"].push_back({{"camera", 0}, {"translation", {0, 3, 3}}, {"rotation", {s, 0, 0, c}}});
  file["nodes"].push_back(
      {{"camera", 1}, {"translation", {0, 10, 0}}, {"rotation", {-std::sqrt(0.5), 0, 0, std::sqrt(0.5)}}});
  file["scenes"][0]["nodes"] = {0, 1, 2};
  file["cameras"] = {{{"type", "perspective"},
                      {"name", "Main View"},
                      {"perspective", {{"yfov", 0.8}, {"aspectRatio", 1.5}, {"znear", 0.1}}}},
                     {{"type", "orthographic"},
                      {"name", "plan"},
                      {"orthographic", {{"xmag", 2}, {"ymag", 2}, {"znear", 0.1}, {"zfar", 20}}}}};
  const auto scene = load(file);
  const Camera& camera = *scene->camera;
  EXPECT_EQ(camera.width(), 640);
  EXPECT_EQ(camera.height(), 427);  // 640 / 1.5
  const Vec3 eye = camera.eye_position();
  EXPECT_NEAR(eye.y, 3, 1e-12);
  EXPECT_NEAR(eye.z, 3, 1e-12);
  const Vec3 gaze = camera.view_direction();
  EXPECT_NEAR(gaze.y, -std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(gaze.z, -std::sqrt(0.5), 1e-12);
  // The vertical field of view is yfov: the top row's centre ray leaves the gaze by yfov/2 less half a pixel.
  const Ray top = camera.generate_ray(320, 0);
  const double off_axis = std::acos(dot(normalize(top.direction), gaze));
  EXPECT_NEAR(off_axis, 0.4 * (1 - 1.0 / 427), 2e-3);
  // Every camera is named (made file-name safe), the orthographic one square.
  ASSERT_EQ(scene->cameras.size(), 2u);
  EXPECT_EQ(scene->cameras[0].name, "Main_View");
  EXPECT_EQ(scene->cameras[1].name, "plan");
  EXPECT_EQ(scene->cameras[1].camera->height(), 640);
  // --set resizes the image: the vertical field stays, the horizontal follows the new aspect.
  const auto wide = load(file, {"camera.width=854", "camera.height=427"});
  const Ray wide_top = wide->camera->generate_ray(427, 0);
  EXPECT_NEAR(std::acos(dot(normalize(wide_top.direction), wide->camera->view_direction())),
              0.4 * (1 - 1.0 / 427), 2e-3);
}

TEST_F(GltfScene, MaterialsBecomeTheDocumentedCookTorranceParametersPerPrimitive) {
  Json file = floor_gltf();
  file["materials"].push_back(
      {{"name", "gold"},
       {"pbrMetallicRoughness",
        {{"baseColorFactor", {1, 0.8, 0.3, 1}}, {"metallicFactor", 1}, {"roughnessFactor", 0.5}}}});
  file["materials"].push_back(
      {{"name", "lamp"},
       {"emissiveFactor", {1, 1, 1}},
       {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 500}}}}}});
  file["materials"].push_back({{"name", "pane"},
                               {"pbrMetallicRoughness", {{"metallicFactor", 0}}},
                               {"extensions",
                                {{"KHR_materials_transmission", {{"transmissionFactor", 0.9}}},
                                 {"KHR_materials_ior", {{"ior", 1.52}}}}}});
  // A second mesh of the same triangles, a metre up, is gold.
  file["meshes"].push_back(file["meshes"][0]);
  file["meshes"][1]["primitives"][0]["material"] = 1;
  file["nodes"].push_back({{"mesh", 1}, {"translation", {0, 1, 0}}});
  file["scenes"][0]["nodes"].push_back(1);
  const GltfSceneDocument translated = gltf_scene_document(write(file), -1, {"scene.gltf", 0, 0, {}});
  const Json& materials = translated.document["materials"];
  // The floor: a dielectric of kd = base colour under facets of F0 0.04, α = roughness².
  EXPECT_EQ(materials["floor"]["kd"], Json({0.5, 0.5, 0.5}));
  EXPECT_EQ(materials["floor"]["roughness"], 1.0);
  EXPECT_EQ(materials["floor"]["ks"], 1.0);
  EXPECT_EQ(materials["floor"]["layered"], true);
  EXPECT_NEAR(materials["floor"]["fresnel_f0"][0].get<double>(), 0.04, 1e-15);
  EXPECT_EQ(materials["floor"]["microfacet"], "ggx");
  // Gold: no diffuse, F0 its colour, α = 0.25.
  EXPECT_EQ(materials["gold"]["kd"], Json({0.0, 0.0, 0.0}));
  EXPECT_EQ(materials["gold"]["ks"], 1.0);
  EXPECT_EQ(materials["gold"]["fresnel_f0"], Json({0.999, 0.8, 0.3}));
  EXPECT_EQ(materials["gold"]["roughness"], 0.25);
  // The pane: 90 % transmitted through a thin sheet of index 1.52 (which reflects by Fresnel
  // itself), a tenth diffuse, nothing left for the reflection lobe.
  EXPECT_EQ(materials["pane"]["kt"], 0.9);
  EXPECT_EQ(materials["pane"]["ior"], 1.52);
  EXPECT_EQ(materials["pane"]["thin"], true);
  EXPECT_NEAR(materials["pane"]["kd"][0].get<double>(), 0.1, 1e-15);
  EXPECT_NEAR(materials["pane"]["ks"].get<double>(), 0.1, 1e-15);
  EXPECT_NEAR(materials["pane"]["fresnel_f0"][0].get<double>(), std::pow(0.52 / 2.52, 2), 1e-15);
  EXPECT_NEAR(materials["pane"]["fresnel_f0"][1].get<double>(), std::pow(0.52 / 2.52, 2), 1e-15);
  // The lamp: 500 cd/m² of white light.
  EXPECT_EQ(materials["lamp"]["emission_luminance"], 500.0);

  const auto scene = load(file);
  ASSERT_EQ(scene->primitives.size(), 4u);
  const auto name_of = [&](std::size_t p) { return scene->materials[scene->primitives[p].material].name; };
  EXPECT_EQ(name_of(0), "floor");
  EXPECT_EQ(name_of(2), "gold");
  // The lamp's exitance is π L / 179 lm/W.
  for (const Material& material : scene->materials)
    if (material.name == "lamp") {
      EXPECT_NEAR(material.emission.g, kPi * 500 / kLuminousEfficacy, 1e-12);
    }
}

// Candela's path tracer divides every lobe by kd + ks + kt where that exceeds 1; a glTF material is
// layered instead (the diffuse beneath the facets' Fresnel): a floor of base 0.8 under 1,000 lx
// straight down shows ρ E (1 − F0) (Candela's pixels are π L) and a little of the facets' F0 = 0.04,
// not 0.8/1.8 of it, as the first mapping (ks = 1, not layered) gave.
TEST_F(GltfScene, ADielectricFloorReflectsItsBaseColourInThePathTracer) {
  Json file = with_light({{"type", "directional"}, {"intensity", 1000}}, {0, 5, 0},
                         {-std::sqrt(0.5), 0, 0, std::sqrt(0.5)});
  file["materials"][0]["pbrMetallicRoughness"]["baseColorFactor"] = {0.8, 0.8, 0.8, 1};
  file["nodes"].push_back(
      {{"camera", 0}, {"translation", {0, 3, 0}}, {"rotation", {-std::sqrt(0.5), 0, 0, std::sqrt(0.5)}}});
  file["scenes"][0]["nodes"].push_back(2);
  file["cameras"] = {
      {{"type", "perspective"}, {"perspective", {{"yfov", 0.3}, {"aspectRatio", 1.0}, {"znear", 0.1}}}}};
  const auto scene = load(file, {"camera.width=8", "camera.height=8", "path.spp=64"});
  const Film film = testing::render_scene(*scene, "path");
  double mean = 0;
  for (int y = 0; y < film.height(); ++y)
    for (int x = 0; x < film.width(); ++x) mean += luminance(film.at(x, y)) / (film.width() * film.height());
  const double diffuse = 0.8 * 1000 / kLuminousEfficacy;
  EXPECT_GT(mean, diffuse * 0.96);
  EXPECT_LT(mean, diffuse * 1.03);
}

TEST_F(GltfScene, WhatCandelaCannotDoIsAnErrorOrAWarning) {
  Json file = floor_gltf();
  file["extensionsUsed"] = {"KHR_materials_clearcoat", "KHR_draco_mesh_compression"};
  file["extensionsRequired"] = {"KHR_draco_mesh_compression"};
  std::string message = error_of(file);
  EXPECT_NE(message.find(
                "extensionsRequired: Candela does not support the extension \"KHR_draco_mesh_compression\""),
            std::string::npos)
      << message;
  file.erase("extensionsRequired");
  file["materials"][0]["normalTexture"] = {{"index", 0}};
  const auto scene = load(file);
  std::string warnings;
  for (const std::string& warning : scene->warnings) warnings += warning + "\n";
  EXPECT_NE(warnings.find("extension \"KHR_materials_clearcoat\" is not supported"), std::string::npos)
      << warnings;
  EXPECT_NE(warnings.find("materials[0].normalTexture: normal maps are not supported yet"), std::string::npos)
      << warnings;
  EXPECT_NE(warnings.find("has no camera"), std::string::npos) << warnings;

  // A missing image names its uri; a scene that does not exist, its number; a bad light, its path.
  Json textured = floor_gltf();
  textured["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", 0}};
  textured["textures"] = {{{"source", 0}}};
  textured["images"] = {{{"uri", "missing.png"}}};
  message = error_of(textured);
  EXPECT_NE(message.find("images[0].uri: 'missing.png' is not a file"), std::string::npos) << message;
  message = error_of(floor_gltf(), {"gltf.scene=3"});
  EXPECT_NE(message.find("has no scene 3 (it has 1: 0 to 0)"), std::string::npos) << message;
  message = error_of(floor_gltf(), {"gltf.zoom=3"});
  EXPECT_NE(message.find("a glTF file takes gltf.scene"), std::string::npos) << message;
  message = error_of(with_light({{"type", "area"}}, {0, 2, 0}));
  EXPECT_NE(message.find("extensions.KHR_lights_punctual.lights[0].type: must be \"point\", \"spot\" or "
                         "\"directional\""),
            std::string::npos)
      << message;
  message = error_of(with_light({{"type", "point"}, {"intensity", -1}}, {0, 2, 0}));
  EXPECT_NE(message.find("lights[0].intensity: must lie in [0, 1e+16]"), std::string::npos) << message;
}

TEST_F(GltfScene, AnImageTextureIsTheBaseColourInSrgbWithItsTransform) {
  Json file = floor_gltf();
  file["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = {
      {"index", 0},
      {"extensions", {{"KHR_texture_transform", {{"offset", {0.25, 0.5}}, {"scale", {2, 4}}}}}}};
  file["textures"] = {{{"source", 0}, {"sampler", 0}}};
  file["samplers"] = {{{"wrapS", 33071}}};
  file["images"] = {{{"uri", "tiles.png"}}};
  std::ofstream(directory_.path() / "tiles.png") << "not read here";
  const GltfSceneDocument translated = gltf_scene_document(write(file), -1, {"scene.gltf", 0, 0, {}});
  const Json& kd = translated.document["materials"]["floor"]["kd"];
  EXPECT_EQ(kd["type"], "image");
  EXPECT_EQ(kd["file"], "tiles.png");
  EXPECT_EQ(kd["encoding"], "srgb");
  EXPECT_EQ(kd["multiplier"], Json({0.5, 0.5, 0.5}));
  EXPECT_EQ(kd["wrap"], "clamp");
  // glTF's v runs down the image, Candela's up: v' = 4 v + (1 − 4 − 0.5).
  EXPECT_EQ(kd["mapping"]["scale"], Json({2.0, 4.0}));
  EXPECT_EQ(kd["mapping"]["offset"], Json({0.25, -3.5}));
}

TEST_F(GltfScene, AMeshEntryNamesTheFilesMaterialsByIndex) {
  // As a JSON scene's mesh: file_materials maps the glTF's material 0 to the scene's "red".
  Json file = floor_gltf();
  write(file, "floor.gltf");
  const std::string scene_text =
      R"({"format": "candela/1", "camera": {}, "materials": {"red": {"kd": [0.8, 0.1, 0.1]}},
    "shapes": [{"type": "mesh", "file": "floor.gltf", "file_materials": ["red"]}]})";
  const auto scene = load_scene_text(scene_text, "scene.json", directory_.path().string());
  EXPECT_EQ(scene->materials[scene->primitives[0].material].name, "red");
  const auto error = [&](const std::string& text) {
    try {
      load_scene_text(text, "scene.json", directory_.path().string());
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(
      error(
          R"({"format": "candela/1", "camera": {}, "shapes": [{"type": "mesh", "file": "floor.gltf", "file_materials": []}]})")
          .find("file_materials: names 0 material(s), but the file's triangles use material 0"),
      std::string::npos);
  EXPECT_NE(
      error(
          R"({"format": "candela/1", "camera": {}, "shapes": [{"type": "mesh", "file": "floor.gltf", "file_materials": ["blue"]}]})")
          .find("unknown material \"blue\""),
      std::string::npos);
}

TEST_F(GltfScene, AJsonSceneIncludesAGltfFileAndOverridesWhatItLacks) {
  // models/floor.gltf: the floor with 100 cd at 2 m; included a metre up, so the light is at y = 3.
  std::filesystem::create_directories(directory_.path() / "models");
  write(with_light({{"type", "point"}, {"intensity", 100}}, {0, 2, 0}), "models/floor.gltf");
  const auto scene_with = [&](const std::string& include, const std::string& rest) {
    return load_scene_text(R"({"format": "candela/1", "include": )" + include + rest + "}", "room.json",
                           directory_.path().string());
  };
  const std::string moved = R"({"file": "models/floor.gltf", "transform": {"translate": [0, 1, 0]}})";
  const auto scene = scene_with(moved, R"(, "materials": {"floor": {"kd": [0.8, 0.1, 0.1]}})");
  // The including file's material of the same name wins; the floor and its light moved up.
  EXPECT_EQ(scene->materials[scene->primitives[0].material].kd->evaluate({}), Color(0.8, 0.1, 0.1));
  EXPECT_NEAR(scene->bounds().lower.y, 1, 1e-12);
  std::vector<ProbePoint> at_floor{{{0, 1, 0}, {0, 1, 0}}};
  ProbeSettings local;
  local.method = "local";
  EXPECT_NEAR(kLuminousEfficacy * luminance(probe(*scene, at_floor, local)[0].irradiance), 25, 1e-9);
  // Its own lights join the file's; "lights": false leaves the file's out.
  const std::string own_light =
      R"(, "lights": [{"type": "point", "position": [0, 3, 0], "luminous_intensity": 50}])";
  EXPECT_NEAR(
      kLuminousEfficacy * luminance(probe(*scene_with(moved, own_light), at_floor, local)[0].irradiance),
      37.5, 1e-9);
  const std::string without =
      R"({"file": "models/floor.gltf", "transform": {"translate": [0, 1, 0]}, "lights": false})";
  EXPECT_NEAR(
      kLuminousEfficacy * luminance(probe(*scene_with(without, own_light), at_floor, local)[0].irradiance),
      12.5, 1e-9);
  // The file has no camera: the including file's is used where it has one, else a framed view.
  EXPECT_NE(scene->warnings.front().find("has no camera"), std::string::npos);
  const auto with_camera = scene_with(moved, R"(, "camera": {"eye": [0, 5, 5], "width": 32, "height": 32})");
  EXPECT_EQ(with_camera->camera->width(), 32);
  for (const std::string& warning : with_camera->warnings)
    EXPECT_EQ(warning.find("has no camera"), std::string::npos);
  // Errors at the include: a missing file, a file that is not glTF, an unknown key.
  const auto error = [&](const std::string& include) {
    try {
      scene_with(include, "");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(error(R"("models/none.gltf")").find("room.json:1:36: include: cannot read glTF file"),
            std::string::npos)
      << error(R"("models/none.gltf")");
  EXPECT_NE(error(R"("models/floor.obj")").find("an include is a glTF file"), std::string::npos);
  EXPECT_NE(error(R"({"file": "models/floor.gltf", "zoom": 2})").find("unknown key \"zoom\""),
            std::string::npos);
}

TEST(PerspectiveCamera, VerticalFieldOfViewGivesTheHorizontalOneOfTheImage) {
  // 90° vertical at 2:1 is 2 atan(2) horizontal; fov and vertical_fov together are refused.
  const auto scene = load_scene_text(R"({"format": "candela/1",
    "camera": {"eye": [0, 0, 0], "target": [0, 0, -1], "vertical_fov": 90, "width": 200, "height": 100}})",
                                     "v.json", ".");
  const Ray right = scene->camera->generate_ray(200, 50);  // the right edge, mid-height
  EXPECT_NEAR(std::atan2(right.direction.x, -right.direction.z), std::atan(2.0), 1e-12);
  EXPECT_THROW(
      load_scene_text(R"({"format": "candela/1", "camera": {"fov": 60, "vertical_fov": 40}})", "v.json", "."),
      InputError);
}

}  // namespace
}  // namespace candela
