#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "integrators/scene_loading.h"
#include "integrators/whitted.h"
#include "io/json_document.h"

namespace candela {
namespace {

// Loads text and returns the error it raises (fails the test when it loads).
InputError load_error(const std::string& text, const std::vector<std::string>& overrides = {}) {
  try {
    load_scene_text(text, "test.json", ".", overrides);
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "expected an InputError for:\n" << text;
  return InputError({}, "none");
}

void expect_error(const std::string& text, const std::string& path, int line, int column,
                  const std::string& message_part) {
  const InputError e = load_error(text);
  EXPECT_EQ(e.location().file, "test.json");
  EXPECT_EQ(e.location().json_path, path) << e.what();
  EXPECT_EQ(e.location().line, line) << e.what();
  EXPECT_EQ(e.location().column, column) << e.what();
  EXPECT_NE(std::string(e.what()).find(message_part), std::string::npos) << e.what();
}

const char* kHeader = R"({
  "format": "candela/1",
  "camera": {"eye": [0, 0, 5], "target": [0, 0, 0], "width": 4, "height": 3},
)";

TEST(SceneLoader, LoadsAMinimalScene) {
  const auto scene = load_scene_text(std::string(kHeader) + R"(
  "lights": [{"type": "point", "position": [0, 5, 0]}, {"type": "ambient", "intensity": 0.25}],
  "materials": {"red": {"kd": [1, 0, 0]}},
  "shapes": [{"type": "sphere", "radius": 2, "material": "red", "transform": [{"translate": [1, 0, 0]}]}]
})",
                                     "test.json", ".");
  EXPECT_EQ(scene->camera->width(), 4);
  EXPECT_EQ(scene->lights.size(), 1u);
  EXPECT_EQ(scene->ambient, Color(0.25));
  ASSERT_EQ(scene->primitives.size(), 1u);
  EXPECT_EQ(scene->materials[scene->primitives[0].material].name, "red");
  EXPECT_NEAR(scene->primitives[0].shape->bounds().upper.x, 3.0, 1e-12);
}

TEST(SceneLoader, SyntaxErrorHasLineAndColumn) {
  const InputError e = load_error("{\n  \"format\": \"candela/1\",\n  \"camera\": {\"width\": 4,}\n}");
  EXPECT_EQ(e.location().line, 3);
  EXPECT_EQ(e.location().column, 25);  // the '}' after the trailing comma
  EXPECT_NE(std::string(e.what()).find("syntax error"), std::string::npos) << e.what();
}

TEST(SceneLoader, UnknownShapeListsTheValidOnes) {
  expect_error(std::string(kHeader) + R"(  "shapes": [{"type": "sphere"}, {"type": "teapot"}]
})",
               "shapes[1].type", 4, 43, "unknown shape \"teapot\" (expected one of: sphere, plane,");
}

TEST(SceneLoader, ReadsAntialiasingSettings) {
  const auto scene = load_scene_text(std::string(kHeader) + R"(  "aa": {"mode": "adaptive", "max_level": 3,
    "threshold": [0.1, 0.2, 0.3], "jitter": true, "filter": "gaussian", "filter_radius": 1, "filter_sigma": 0.4}
})",
                                     "test.json", ".");
  EXPECT_EQ(scene->antialiasing.mode, AntialiasingMode::adaptive);
  EXPECT_EQ(scene->antialiasing.max_level, 3);
  EXPECT_EQ(scene->antialiasing.threshold, Color(0.1, 0.2, 0.3));
  EXPECT_TRUE(scene->antialiasing.jitter);
  EXPECT_EQ(scene->antialiasing.filter, "gaussian");
  EXPECT_EQ(scene->antialiasing.filter_parameters.sigma, 0.4);
  const auto plain = load_scene_text(std::string(kHeader) + R"(  "shapes": []
})",
                                     "test.json", ".");
  EXPECT_EQ(plain->antialiasing.mode, AntialiasingMode::none);
}

TEST(SceneLoader, BadAntialiasingSettings) {
  expect_error(std::string(kHeader) + R"(  "aa": {"mode": "supersampled"}
})",
               "aa.mode", 4, 18,
               "unknown anti-aliasing mode \"supersampled\" (expected one of: none, uniform,");
  expect_error(std::string(kHeader) + R"(  "aa": {"mode": "uniform", "n": 0}
})",
               "aa.n", 4, 34, "n");
  expect_error(std::string(kHeader) + R"(  "aa": {"threshold": [0.2, -0.1, 0.3]}
})",
               "aa.threshold[1]", 4, 29, "");
  expect_error(std::string(kHeader) + R"(  "aa": {"filter": "sinc"}
})",
               "aa.filter", 4, 20, "unknown filter \"sinc\"");
  expect_error(std::string(kHeader) + R"(  "aa": {"nn": 2}
})",
               "aa.nn", 4, 16, "unknown key \"nn\"");
}

TEST(SceneLoader, UnknownKeyIsAnError) {
  expect_error(std::string(kHeader) + R"(  "shapes": [{"type": "sphere", "radus": 2}]
})",
               "shapes[0].radus", 4, 42, "unknown key \"radus\"");
  expect_error(std::string(kHeader) + R"(  "lightz": []
})",
               "lightz", 4, 13, "unknown key \"lightz\"");
}

TEST(SceneLoader, NegativeRadius) {
  expect_error(std::string(kHeader) + R"(  "shapes": [
    {"type": "sphere", "radius": -1}
  ]
})",
               "shapes[0].radius", 5, 34, "must be > 0");
}

TEST(SceneLoader, FieldOfViewOutOfRange) {
  expect_error(R"({"format": "candela/1",
 "camera": {"fov": 180}})",
               "camera.fov", 2, 20, "must be in (0, 180)");
}

TEST(SceneLoader, MissingMeshFile) {
  expect_error(std::string(kHeader) + R"(  "shapes": [{"type": "mesh", "file": "no/such/mesh.obj"}]
})",
               "shapes[0].file", 4, 39, "no/such/mesh.obj");
}

TEST(SceneLoader, NaNIsRejected) {
  // JSON has no NaN literal: the parser rejects the bare word with its position.
  const InputError bare = load_error(std::string(kHeader) + R"(  "ambient": NaN
})");
  EXPECT_EQ(bare.location().line, 4);
  EXPECT_EQ(bare.location().column, 14);
  // A string where a number belongs is a type error at its path.
  expect_error(std::string(kHeader) + R"(  "ambient": [0, "NaN", 0]
})",
               "ambient[1]", 4, 18, "expected a number");
}

TEST(SceneLoader, OverflowingNumberIsRejected) {
  const InputError e = load_error(std::string(kHeader) + R"(  "ambient": 1e999
})");
  EXPECT_EQ(e.location().line, 4);
}

TEST(SceneLoader, WrongTypesAndMissingKeys) {
  expect_error(R"({"format": "candela/1", "camera": {"width": "wide"}})", "camera.width", 1, 45,
               "expected a number");
  expect_error(R"({"format": "candela/1", "camera": {"width": 2.5}})", "camera.width", 1, 45,
               "expected an integer");
  expect_error(R"({"format": "candela/2", "camera": {}})", "format", 1, 12, "unsupported format");
  expect_error(R"({"camera": {}})", "", 1, 1, "missing required key \"format\"");
  expect_error(std::string(kHeader) + R"(  "lights": [{"type": "point"}]
})",
               "lights[0]", 4, 14, "missing required key \"position\"");
}

TEST(SceneLoader, UnknownMaterialReference) {
  expect_error(std::string(kHeader) + R"(  "materials": {"red": {"kd": [1, 0, 0]}},
  "shapes": [{"type": "sphere", "material": "blue"}]
})",
               "shapes[0].material", 5, 45, "unknown material \"blue\" (defined: red)");
}

TEST(SceneLoader, DuplicateKeyIsAnError) {
  const InputError e = load_error(R"({"format": "candela/1", "format": "candela/1"})");
  EXPECT_EQ(e.location().column, 25);
  EXPECT_NE(std::string(e.what()).find("duplicate key"), std::string::npos);
}

TEST(SceneLoader, BadValuesInMaterialsLightsAndTransforms) {
  expect_error(std::string(kHeader) + R"(  "materials": {"m": {"kr": 1.5}}
})",
               "materials.m.kr", 4, 29, "must be in [0, 1]");
  expect_error(
      std::string(kHeader) + R"(  "lights": [{"type": "point", "position": [0, 1, 0], "attenuation": "cubic"}]
})",
      "lights[0].attenuation", 4, 70, "unknown attenuation");
  expect_error(std::string(kHeader) + R"(  "shapes": [{"type": "sphere", "transform": [{"scale": 0}]}]
})",
               "shapes[0].transform[0].scale", 4, 57, "non-zero");
  expect_error(
      std::string(kHeader) +
          R"(  "shapes": [{"type": "sphere", "transform": [{"matrix": [1,0,0,0, 0,1,0,0, 0,0,0,0, 0,0,0,1]}]}]
})",
      "shapes[0].transform[0].matrix", 4, 58, "singular");
  expect_error(std::string(kHeader) + R"(  "film": {"out_of_range": "wrap"}
})",
               "film.out_of_range", 4, 28, "expected one of: clamp, scale, normalize");
}

// Directions read from the scene are normalised by direction_of (math/direction.h): a
// light direction, rotation axis or plane normal of components of 1e-200 (a squared length that
// underflows to 0) was refused as "must be non-zero". They are directions; zero still is refused.
TEST(SceneLoader, DirectionsOfTinyComponentsAreDirections) {
  const auto scene = load_scene_text(std::string(kHeader) + R"(
  "lights": [{"type": "directional", "direction": [0, -1e-200, 0]}],
  "shapes": [{"type": "plane", "normal": [0, 1e-200, 0]},
             {"type": "sphere", "transform": [{"translate": [2, 0, 0]}, {"rotate": {"angle": 90, "axis": [0, 0, 1e-200]}}]}]
})",
                                     "test.json", ".");
  EXPECT_EQ(scene->lights.size(), 1u);
  ASSERT_EQ(scene->primitives.size(), 2u);
  const Bounds3 sphere = scene->primitives[1].shape->bounds();
  EXPECT_NEAR(
      std::max(std::fabs(sphere.upper.x + sphere.lower.x), std::fabs(sphere.upper.y + sphere.lower.y)), 4,
      1e-9);
  expect_error(std::string(kHeader) + R"(  "lights": [{"type": "directional", "direction": [0, 0, 0]}]
})",
               "lights[0].direction", 4, 51, "must be non-zero");
}

TEST(SceneLoader, ConstructorValidationIsReportedAtTheShape) {
  expect_error(
      std::string(kHeader) + R"(  "shapes": [{"type": "cylinder", "base": [0, 0, 0], "cap": [0, 0, 0]}]
})",
      "shapes[0]", 4, 14, "base and cap must differ");
}

TEST(SceneLoader, OverridesReplaceSettingsByDottedPath) {
  const auto scene = load_scene_text(std::string(kHeader) + R"(  "shapes": [{"type": "sphere"}]
})",
                                     "test.json", ".",
                                     {"camera.width=640", "whitted.max_depth=3", "film.out_of_range=scale",
                                      "shapes.0.radius=2.5", "background=[0.1, 0.2, 0.3]"});
  EXPECT_EQ(scene->camera->width(), 640);
  EXPECT_EQ(read_whitted_settings(scene->plugin_settings.node("whitted")).max_depth, 3);
  EXPECT_EQ(scene->display.out_of_range, OutOfRange::scale);
  EXPECT_NEAR(scene->primitives[0].shape->bounds().upper.x, 2.5, 1e-12);
  EXPECT_EQ(scene->background, Color(0.1, 0.2, 0.3));
}

// An unknown top-level key made by --set (a misspelt method) was blamed on the scene
// file's opening brace; it names the assignment, as nested keys do.
TEST(SceneLoader, UnknownTopLevelKeyFromAnOverrideNamesTheAssignment) {
  const InputError e = load_error(std::string(kHeader) + "\"shapes\": []}", {"whited.max_depth=1"});
  EXPECT_EQ(e.location().file, "--set whited.max_depth=1") << e.what();
  EXPECT_EQ(e.location().line, 0);
  EXPECT_NE(std::string(e.what()).find("unknown key \"whited\""), std::string::npos) << e.what();
}

// Each method's and accelerator's object is read by its own registry entry, still at load time and
// still with the file position (the scene keeps the raw objects, not the structs).
TEST(SceneLoader, PluginSettingsAreCheckedAtLoadTime) {
  expect_error(std::string(kHeader) + "  \"whitted\": {\"max_dept\": 3}\n}", "whitted.max_dept", 4, 27,
               "unknown key \"max_dept\"");
  expect_error(std::string(kHeader) + "  \"path\": {\"spp\": -1}\n}", "path.spp", 4, 19,
               "must be in [0, 16777216]");
  expect_error(std::string(kHeader) + "  \"bvh\": {\"bins\": 1}\n}", "bvh.bins", 4, 19,
               "must be in [2, 256]");
  expect_error(std::string(kHeader) + "  \"octree\": {\"depth\": 3}\n}", "octree.depth", 4, 23,
               "unknown key \"depth\"");
  // A method whose object is not used still has it checked, and --set reaches it.
  const InputError override =
      load_error(std::string(kHeader) + "\"shapes\": []}", {"radiosity.solver=jacobi"});
  EXPECT_EQ(override.location().file, "--set radiosity.solver=jacobi") << override.what();
  // The objects are kept for the plugins, overrides applied.
  const auto scene = load_scene_text(std::string(kHeader) + "  \"whitted\": {\"max_depth\": 2}\n}",
                                     "test.json", ".", {"whitted.shadows=false"});
  const WhittedSettings whitted = read_whitted_settings(scene->plugin_settings.node("whitted"));
  EXPECT_EQ(whitted.max_depth, 2);
  EXPECT_FALSE(whitted.shadows);
  EXPECT_EQ(read_whitted_settings(scene->plugin_settings.node("local")).max_depth, 5);  // absent: defaults
}

TEST(SceneLoader, BadOverridesNameTheAssignment) {
  const InputError e = load_error(std::string(kHeader) + "\"shapes\": []}", {"camera.width=-3"});
  EXPECT_EQ(e.location().file, "--set camera.width=-3");
  EXPECT_EQ(e.location().json_path, "camera.width");
  const InputError typo = load_error(std::string(kHeader) + "\"shapes\": []}", {"camer.width=3"});
  EXPECT_NE(std::string(typo.what()).find("unknown key \"camer\""), std::string::npos) << typo.what();
  const InputError no_equals = load_error(std::string(kHeader) + "\"shapes\": []}", {"camera.width"});
  EXPECT_NE(std::string(no_equals.what()).find("key=value"), std::string::npos);
  const InputError range = load_error(std::string(kHeader) + "\"shapes\": []}", {"shapes.4.radius=1"});
  EXPECT_NE(std::string(range.what()).find("out of range"), std::string::npos);
}

TEST(SceneLoader, MissingSceneFile) {
  try {
    load_scene_file("/nonexistent/scene.json");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.location().file, "/nonexistent/scene.json");
    EXPECT_NE(std::string(e.what()).find("cannot open"), std::string::npos);
  }
}

TEST(SceneLoader, MeshPathIsRelativeToTheSceneFile) {
  const auto directory =
      std::filesystem::temp_directory_path() / ("candela-loader-test-" + std::to_string(::getpid()));
  std::filesystem::create_directories(directory / "meshes");
  {
    std::ofstream obj(directory / "meshes" / "quad.obj");
    obj << "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";
    std::ofstream scene(directory / "scene.json");
    scene << kHeader
          << R"(  "shapes": [{"type": "mesh", "file": "meshes/quad.obj", "transform": {"scale": 2}}]})";
  }
  const auto scene = load_scene_file((directory / "scene.json").string());
  EXPECT_EQ(scene->primitives.size(), 2u);
  EXPECT_EQ(scene->objects.size(), 1u);
  EXPECT_NEAR(scene->bounds().upper.x, 2.0, 1e-12);
  std::filesystem::remove_all(directory);
}

TEST(SceneLoader, ReadsNamedCamerasThatInheritTheImageSize) {
  const auto scene = load_scene_text(std::string(kHeader) + R"(  "cameras": [
    {"name": "front", "fov": 40},
    {"name": "side_2", "eye": [5, 0, 0], "width": 8},
    {"name": "plan", "type": "orthographic", "eye": [0, 5, 0], "up": [0, 0, -1], "height": 6}
  ]
})",
                                     "test.json", ".");
  EXPECT_EQ(scene->camera->width(), 4);  // "camera" is still the one rendered
  ASSERT_EQ(scene->cameras.size(), 3u);
  EXPECT_EQ(scene->cameras[0].name, "front");
  EXPECT_EQ(scene->cameras[0].camera->width(), 4);
  EXPECT_EQ(scene->cameras[0].camera->height(), 3);
  EXPECT_EQ(scene->cameras[1].name, "side_2");
  EXPECT_EQ(scene->cameras[1].camera->width(), 8);
  EXPECT_EQ(scene->cameras[1].camera->height(), 3);
  EXPECT_EQ(scene->cameras[1].camera->eye_position(), Vec3(5, 0, 0));
  EXPECT_EQ(scene->cameras[2].camera->type_name(), "orthographic");
  EXPECT_EQ(scene->cameras[2].camera->width(), 4);
  EXPECT_EQ(scene->cameras[2].camera->height(), 6);
  // Only the size is inherited: eye is the default, not the eye of "camera".
  const auto moved = load_scene_text(R"({"format": "candela/1", "camera": {"eye": [1, 2, 3]},
    "cameras": [{"name": "a"}]})",
                                     "test.json", ".");
  EXPECT_EQ(moved->cameras[0].camera->eye_position(), Vec3(0, 0, 5));
  EXPECT_EQ(moved->cameras[0].camera->width(), 640);
  // --set camera.width resizes the views that do not fix their own width.
  const auto resized =
      load_scene_text(std::string(kHeader) + R"(  "cameras": [{"name": "a"}, {"name": "b", "width": 2}]
})",
                      "test.json", ".", {"camera.width=10"});
  EXPECT_EQ(resized->cameras[0].camera->width(), 10);
  EXPECT_EQ(resized->cameras[1].camera->width(), 2);
  const auto none = load_scene_text(std::string(kHeader) + R"(  "shapes": []
})",
                                    "test.json", ".");
  EXPECT_TRUE(none->cameras.empty());
}

TEST(SceneLoader, BadNamedCamerasAreLocatedErrors) {
  const std::string header = kHeader;
  expect_error(header + R"(  "cameras": [
    {"name": "a"},
    {"name": "a"}
  ]
})",
               "cameras[1].name", 6, 14, "duplicate camera name \"a\" (cameras[0] has it already)");
  expect_error(header + R"(  "cameras": [
    {"fov": 30}
  ]
})",
               "cameras[0]", 5, 5, "missing required key \"name\"");
  expect_error(header + R"(  "cameras": [
    {"name": "my camera"}
  ]
})",
               "cameras[0].name", 5, 14, "may only use letters, digits, '_' and '-'");
  expect_error(header + R"(  "cameras": [
    {"name": ""}
  ]
})",
               "cameras[0].name", 5, 14, "must not be empty");
  expect_error(header + R"(  "cameras": [
    {"name": "all"}
  ]
})",
               "cameras[0].name", 5, 14, "reserved");
  expect_error(header + R"(  "cameras": [
    {"name": "default"}
  ]
})",
               "cameras[0].name", 5, 14, "reserved");
  expect_error(header + R"(  "cameras": [
    {"name": 7}
  ]
})",
               "cameras[0].name", 5, 14, "expected a string");
  // The keys of "camera" are read by the same reader, with the same checks.
  expect_error(header + R"(  "cameras": [
    {"name": "a"},
    {"name": "b", "fov": 200}
  ]
})",
               "cameras[1].fov", 6, 26, "must be in (0, 180)");
  expect_error(header + R"(  "cameras": [
    {"name": "b", "zoom": 2}
  ]
})",
               "cameras[0].zoom", 5, 27,
               "unknown key \"zoom\" (expected one of: eye, fov, height, mirrored, name, target, type, up, "
               "vertical_fov, width)");
  expect_error(header + R"(  "cameras": [
    {"name": "b", "type": "fisheye"}
  ]
})",
               "cameras[0].type", 5, 27, "unknown camera \"fisheye\"");
  expect_error(header + R"(  "cameras": {"name": "a"}
})",
               "cameras", 4, 14, "expected an array");
  expect_error(header + R"(  "cameras": [3]
})",
               "cameras[0]", 4, 15, "expected an object");
}

TEST(SceneLoader, TheSeedScenesLoad) {
  for (const char* name : {"two-mirrors.json", "glass-globe.json"}) {
    const auto scene = load_scene_file(std::string(CANDELA_SOURCE_DIR) + "/scenes/" + name);
    EXPECT_GT(scene->primitives.size(), 3u) << name;
  }
  const auto builtin = load_default_scene();
  // 000 §5.9: 9 spheres, 9 cylinders, 2 polygons, 2 discs, and the wall and floor planes.
  int spheres = 0, cylinders = 0, polygons = 0, discs = 0, planes = 0;
  for (const auto& object : builtin->objects) {
    spheres += object.type == "sphere";
    cylinders += object.type == "cylinder";
    polygons += object.type == "polygon";
    discs += object.type == "disc";
    planes += object.type == "plane";
  }
  EXPECT_EQ(spheres, 9);
  EXPECT_EQ(cylinders, 9);
  EXPECT_EQ(polygons, 2);
  EXPECT_EQ(discs, 2);
  EXPECT_EQ(planes, 2);
  EXPECT_EQ(builtin->lights.size(), 2u);
  EXPECT_EQ(builtin->ambient, Color(0.3));
  EXPECT_EQ(read_whitted_settings(builtin->plugin_settings.node("whitted")).max_depth, 12);
}

TEST(SceneLoader, ReviewedHostileInputsAreLocatedErrors) {
  // Nesting too deep to be a scene: refused before it eats memory.
  const InputError deep = load_error(std::string(300, '[') + std::string(300, ']'));
  EXPECT_NE(std::string(deep.what()).find("nesting deeper than 256"), std::string::npos) << deep.what();
  // Small scales are valid (they used to be called singular); dependent columns are not.
  EXPECT_NO_THROW(load_scene_text(
      std::string(kHeader) + R"("shapes": [{"type": "sphere", "transform": {"scale": 1e-4}}]})", "test.json",
      "."));
  EXPECT_NO_THROW(load_scene_text(
      std::string(kHeader) + R"("shapes": [{"type": "sphere", "transform": {"scale": [1, 1, 1e-12]}}]})",
      "test.json", "."));
  expect_error(
      std::string(kHeader) +
          R"(  "shapes": [{"type": "sphere", "transform": {"matrix": [1, 2, 0, 0,  1, 2, 0, 0,  0, 0, 1, 0,  0, 0, 0, 1]}}]
})",
      "shapes[0].transform.matrix", 4, 57, "singular");
  // Magnitudes whose squares would overflow, and images too large for memory.
  expect_error(std::string(kHeader) + R"(  "shapes": [{"type": "sphere", "radius": 1e200}]
})",
               "shapes[0].radius", 4, 43, "magnitude above 1e16");
  expect_error(R"({"format": "candela/1", "camera": {"width": 65536, "height": 65536}})", "camera.width", 1,
               45, "lower camera.width or camera.height");
  // A ray tree that would never shrink.
  expect_error(std::string(kHeader) + R"(  "materials": {"m": {"kr": 0.6, "kt": 0.6}}
})",
               "materials.m.kt", 4, 40, "kr + kt must be <= 1");
  // A thin sheet is kt's: without it nothing passes; and it has no inside to absorb in.
  expect_error(std::string(kHeader) + R"(  "materials": {"m": {"thin": true}}
})",
               "materials.m.thin", 4, 31, "a thin sheet needs kt");
  expect_error(
      std::string(kHeader) + R"(  "materials": {"m": {"kt": 1, "thin": true, "absorption": [1, 1, 1]}}
})",
      "materials.m.absorption", 4, 60, "a thin sheet has no inside");
}

TEST(SceneLoader, OverridesWithOutOfRangeNumbersAndIndices) {
  const std::string text = std::string(kHeader) + R"("shapes": [{"type": "sphere"}]})";
  const InputError huge = load_error(text, {"camera.fov=1e999"});
  EXPECT_NE(std::string(huge.what()).find("out of range"), std::string::npos) << huge.what();
  const InputError index = load_error(text, {"shapes.99999999999999999999999.radius=2"});
  EXPECT_NE(std::string(index.what()).find("out of range"), std::string::npos) << index.what();
  const InputError file_overflow = load_error(std::string(kHeader) + R"(  "ambient": 1e999})");
  EXPECT_EQ(std::string(file_overflow.message()).find("[json.exception"), std::string::npos)
      << file_overflow.what();
}

TEST(SceneLoader, MtlValuesAreRangeChecked) {
  const auto directory =
      std::filesystem::temp_directory_path() / ("candela-mtl-test-" + std::to_string(::getpid()));
  std::filesystem::create_directories(directory);
  std::ofstream(directory / "m.obj") << "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl bad\nf 1 2 3\n";
  std::ofstream(directory / "m.mtl") << "newmtl bad\nKd -5 0.5 0.5\n";
  const std::string text = std::string(kHeader) + R"("shapes": [{"type": "mesh", "file": "m.obj"}]})";
  try {
    load_scene_text(text, "test.json", directory.string());
    ADD_FAILURE() << "negative Kd accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.location().json_path, "shapes[0].file");
    EXPECT_NE(std::string(e.what()).find("Ka, Kd and Ke must be >= 0"), std::string::npos) << e.what();
  }
  std::filesystem::remove_all(directory);
}

TEST(JsonDocument, RecordsWhereEveryValueStarts) {
  const JsonDocument document = JsonDocument::parse(
      "{\n  // a comment\n  \"a\": [1, 2.5,\n     {\"b\": true}],\n  /* more */ \"c\": \"x\"\n}", "f.json");
  auto at = [&](const std::string& path) {
    const SourceLocation l = document.locate(path);
    return std::make_pair(l.line, l.column);
  };
  EXPECT_EQ(at("a"), std::make_pair(3, 8));
  EXPECT_EQ(at("a[0]"), std::make_pair(3, 9));
  EXPECT_EQ(at("a[1]"), std::make_pair(3, 12));
  EXPECT_EQ(at("a[2]"), std::make_pair(4, 6));
  EXPECT_EQ(at("a[2].b"), std::make_pair(4, 12));
  EXPECT_EQ(at("c"), std::make_pair(5, 19));
  // A default value not in the file is reported at its nearest ancestor.
  EXPECT_EQ(at("a[2].missing"), std::make_pair(4, 6));
}

// Every step legal, their product not — 25 × "scale 1e16" overflowed to a black image with
// bounds (0,0,0)–(0,0,0) and exit 0 (scale 0 alone was refused); 25 × 1e-16 underflowed. The
// composed transform is held to the bounds of a single scene number (1e16, 1e-16 for a scale).
TEST(SceneLoader, AComposedTransformThatOverflowsUnderflowsOrIsIllConditionedIsRefused) {
  const auto repeated = [](const std::string& step, int times) {
    std::string steps;
    for (int i = 0; i < times; ++i) steps += (i ? ", " : "") + step;
    return "[" + steps + "]";
  };
  const auto scene = [](const std::string& transform) {
    return std::string(kHeader) + R"(  "shapes": [{"type": "sphere", "transform": )" + transform + "}]\n}";
  };
  const struct {
    std::string transform, message;
  } cases[] = {
      {repeated(R"({"scale": 1e16})", 25), "overflows: an entry reaches inf, above 1e+16"},
      {repeated(R"({"scale": 1e16})", 2), "overflows: an entry reaches 1e+32"},
      {repeated(R"({"translate": [1e16, 0, 0]})", 2), "overflows: an entry reaches 2e+16"},
      {repeated(R"({"scale": 1e-16})", 25), "underflows: it shrinks a direction to 0 of its length"},
      {repeated(R"({"scale": 1e-9})", 2), "underflows: it shrinks a direction to 1e-18"},
      {R"([{"scale": [1e7, 1, 1]}, {"scale": [1, 1e-7, 1]}])", "stretches one direction 1e+14 times"},
      {R"({"scale": [1e13, 1, 1]})", "at most 1e+12"},
  };
  for (const auto& c : cases) {
    const InputError e = load_error(scene(c.transform));
    EXPECT_EQ(e.location().json_path, "shapes[0].transform") << e.what();
    EXPECT_EQ(e.location().line, 4) << e.what();
    EXPECT_NE(std::string(e.what()).find(c.message), std::string::npos) << e.what();
  }
  // Large but sound products still load: 2 × 1e8 (1e16, uniform), 2 × 1e-8, a stretch of 1e11.
  EXPECT_NO_THROW(load_scene_text(scene(repeated(R"({"scale": 1e8})", 2)), "test.json", "."));
  EXPECT_NO_THROW(load_scene_text(scene(repeated(R"({"scale": 1e-8})", 2)), "test.json", "."));
  EXPECT_NO_THROW(load_scene_text(scene(R"({"scale": [1e11, 1, 1]})"), "test.json", "."));
}

}  // namespace
}  // namespace candela
