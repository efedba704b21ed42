// pbrt-v4 scene files as whole scenes (io/pbrt_scene.h): the hand-written Cornell box renders as
// the JSON one, every method draws both scenes of scenes/pbrt/, lights keep pbrt's radiometry, the
// camera keeps pbrt's left-handed image, and bad input is an error or a warning at file:line.
#include "io/pbrt_scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "integrators/probe.h"
#include "integrators/scene_loading.h"
#include "io/pbrt_spectra.h"
#include "math/constants.h"
#include "render_support.h"
#include "scene/scene.h"
#include "scratch_directory.h"

namespace candela {
namespace {

using Json = nlohmann::json;

const std::string kScenes = std::string(CANDELA_SOURCE_DIR) + "/scenes/";

class PbrtScene : public ::testing::Test {
 protected:
  std::string write(const std::string& text, const std::string& name = "scene.pbrt") {
    const std::string path = (directory_.path() / name).string();
    std::ofstream(path) << text;
    return path;
  }
  // The InputError of translating `text`, or a failure.
  InputError error_of(const std::string& text, const std::string& name = "scene.pbrt") {
    const std::string path = write(text, name);
    try {
      pbrt_scene_document(path);
    } catch (const InputError& e) {
      return e;
    }
    ADD_FAILURE() << "no error for:\n" << text;
    return InputError({}, "none");
  }
  std::vector<std::string> warnings_of(const std::string& text) {
    return pbrt_scene_document(write(text)).warnings;
  }
  static bool any_contains(const std::vector<std::string>& warnings, const std::string& part) {
    for (const std::string& w : warnings)
      if (w.find(part) != std::string::npos) return true;
    return false;
  }
  testing::ScratchDirectory directory_{"candela-pbrt-scene"};
};

// The header every small test scene starts with: a 16 × 16 view of the origin from +z.
const std::string kView = R"(LookAt 0 0 5  0 0 0  0 1 0
Camera "perspective" "float fov" [40]
Film "rgb" "integer xresolution" [16] "integer yresolution" [16]
WorldBegin
)";

TEST_F(PbrtScene, TheCornellBoxEqualsTheJsonScene) {
  // Bilinear patches that are parallelograms become the JSON's quads, the lamp's L = 12/π its
  // emission 12, the Scale -1 1 1 + LookAt camera its eye, target and up. The small box is six
  // quads here and a box there: a few hit points differ in their last bits, so the film's doubles
  // agree to 1e-6 (written as float PFM, `candela render -o x.pfm`, the bytes are the same).
  const std::vector<std::string> small = {"camera.width=32", "camera.height=32", "path.spp=4"};
  const auto from_pbrt = load_scene_file(kScenes + "pbrt/cornell-box.pbrt", small);
  const auto from_json = load_scene_file(kScenes + "cornell-box.json", small);
  const Film a = testing::render_scene(*from_pbrt, "path");
  const Film b = testing::render_scene(*from_json, "path");
  double sum = 0;
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x) {
      ASSERT_NEAR(a.at(x, y).r, b.at(x, y).r, 1e-6 * b.at(x, y).r) << x << ", " << y;
      ASSERT_NEAR(a.at(x, y).g, b.at(x, y).g, 1e-6 * b.at(x, y).g) << x << ", " << y;
      ASSERT_NEAR(a.at(x, y).b, b.at(x, y).b, 1e-6 * b.at(x, y).b) << x << ", " << y;
      sum += a.at(x, y).r;
    }
  EXPECT_GT(sum / (32 * 32), 0.05);  // a lit room, not two black images
}

TEST_F(PbrtScene, EveryMethodRendersBothScenes) {
  const std::vector<std::string> small = {"camera.width=24",
                                          "camera.height=24",
                                          "path.spp=2",
                                          "radiosity.hemicube_resolution=16",
                                          "meshless.grid=12",
                                          "meshless.rounds=1",
                                          "meshless.gather_rays=16"};
  for (const char* file : {"pbrt/cornell-box.pbrt", "pbrt/instanced-still-life.pbrt"}) {
    const auto scene = load_scene_file(kScenes + file, small);
    for (const char* method : {"local", "whitted", "raster", "radiosity", "meshless", "path"}) {
      const Film film = testing::render_scene(*scene, method);
      double sum = 0;
      bool finite = true;
      for (int y = 0; y < film.height(); ++y)
        for (int x = 0; x < film.width(); ++x) {
          const Color& c = film.at(x, y);
          finite = finite && std::isfinite(c.r) && std::isfinite(c.g) && std::isfinite(c.b);
          sum += c.r + c.g + c.b;
        }
      EXPECT_TRUE(finite) << file << " " << method;
      EXPECT_GT(sum, 0) << file << " " << method;
    }
  }
}

TEST_F(PbrtScene, TheStillLifeInstancesItsObjectAndReadsItsMaterials) {
  const PbrtSceneDocument translated = pbrt_scene_document(kScenes + "pbrt/instanced-still-life.pbrt");
  const Json& document = translated.document;
  // Three instances of the ball (radius 0.35) at the instances' translations, one glass ball.
  std::vector<std::vector<double>> centres;
  for (const Json& shape : document["shapes"])
    if (shape["type"] == "sphere" && shape["radius"] == 0.35) {
      const Json& m = shape["transform"]["matrix"];
      centres.push_back({m[3].get<double>(), m[7].get<double>(), m[11].get<double>()});
      EXPECT_TRUE(shape["material"] == "copper" || shape["material"] == "gold");
    }
  ASSERT_EQ(centres.size(), 3u);
  EXPECT_NEAR(centres[0][0], -2.2, 1e-12);
  EXPECT_NEAR(centres[1][0], -1.4, 1e-12);  // the second Translate composes with the first
  EXPECT_NEAR(centres[2][0], 0.6, 1e-12);
  EXPECT_NEAR(centres[2][1], 0.35, 1e-12);
  const Json& copper = document["materials"]["copper"];
  EXPECT_EQ(copper["type"], "cook-torrance");
  EXPECT_EQ(copper["fresnel_ior"][0].get<double>(), (*pbrt_metal_spectrum("metal-Cu-eta"))[0]);
  EXPECT_EQ(copper["fresnel_k"][2].get<double>(), (*pbrt_metal_spectrum("metal-Cu-k"))[2]);
  EXPECT_NEAR(copper["roughness"].get<double>(), std::sqrt(0.02), 1e-12);  // remaproughness
  const Json& floor = document["materials"]["material-1"]["kd"];
  EXPECT_EQ(floor["type"], "image");
  EXPECT_EQ(floor["file"], "../textures/tiles.png");
  EXPECT_EQ(floor["mapping"]["scale"], Json::array({4, 4}));
  EXPECT_EQ(document["materials"]["material-2"]["kt"], 1);
  EXPECT_EQ(document["path"]["spp"], 32);
  EXPECT_EQ(document["path"]["max_depth"], 8);
  EXPECT_EQ(document["camera"]["vertical_fov"], 40);  // landscape: pbrt's fov is the vertical one
  EXPECT_EQ(document["camera"]["mirrored"], true);
  EXPECT_TRUE(any_contains(translated.warnings, "instanced-still-life.pbrt:12: Integrator \"volpath\""));
}

TEST_F(PbrtScene, APointLightGivesIOverDistanceSquaredAndAnEmitterShowsPiL) {
  // A point light of I = 5 (× scale 2) 2 above a floor: E = 10/4 W/m² below it, 10·cos³θ/4 aside.
  const auto scene = load_scene_file(write(kView + R"(
LightSource "point" "point3 from" [0 2 0] "rgb I" [5 5 5] "float scale" [2]
Shape "bilinearmesh" "point3 P" [-5 0 5  5 0 5  -5 0 -5  5 0 -5]
)"));
  std::vector<ProbePoint> points = {{{0, 0, 0}, {0, 1, 0}}, {{2, 0, 0}, {0, 1, 0}}};
  ProbeSettings settings;
  settings.method = "local";
  const std::vector<ProbeResult> results = probe(*scene, points, settings);
  EXPECT_NEAR(results[0].irradiance.r, 10.0 / 4, 1e-9);
  EXPECT_NEAR(results[1].irradiance.g, 10.0 * std::pow(2 / std::sqrt(8.0), 3) / 4, 1e-9);

  // A diffuse area light of L = 0.5 filling the view: Candela shows π·L (its pixels are π × radiance).
  const auto lamp = load_scene_file(write(kView + R"(
AreaLightSource "diffuse" "rgb L" [0.5 0.25 1]
Material "diffuse" "rgb reflectance" [0 0 0]
Shape "bilinearmesh" "point3 P" [-9 -9 0  9 -9 0  -9 9 0  9 9 0]
)"));
  const Film film = testing::render_scene(*lamp, "path");
  EXPECT_NEAR(film.at(8, 8).r, kPi * 0.5, 1e-9);
  EXPECT_NEAR(film.at(8, 8).g, kPi * 0.25, 1e-9);
  EXPECT_NEAR(film.at(8, 8).b, kPi * 1, 1e-9);
}

// How bright the image's left and right halves are.
std::pair<double, double> left_and_right(const Film& film) {
  double left = 0, right = 0;
  for (int y = 0; y < film.height(); ++y)
    for (int x = 0; x < film.width(); ++x) (x < film.width() / 2 ? left : right) += film.at(x, y).r;
  return {left, right};
}

TEST_F(PbrtScene, TheCameraIsLeftHandedAsPbrtsUnlessScaledByMinusOneInX) {
  // A glowing ball at world +x. pbrt's camera +x is up × gaze = −x here: the ball is on the LEFT of
  // pbrt's image; with Scale -1 1 1 before the LookAt (the right-handed view) on the right.
  const std::string world = R"(
WorldBegin
AreaLightSource "diffuse" "rgb L" [1 1 1]
Translate 1.2 0 0
Shape "sphere" "float radius" [0.6]
)";
  const std::string film = R"(Camera "perspective" "float fov" [60]
Film "rgb" "integer xresolution" [24] "integer yresolution" [16]
)";
  const auto plain = load_scene_file(write("LookAt 0 0 5  0 0 0  0 1 0\n" + film + world, "plain.pbrt"));
  const auto [plain_left, plain_right] = left_and_right(testing::render_scene(*plain, "local"));
  EXPECT_GT(plain_left, 0);
  EXPECT_EQ(plain_right, 0);

  const auto scaled =
      load_scene_file(write("Scale -1 1 1\nLookAt 0 0 5  0 0 0  0 1 0\n" + film + world, "scaled.pbrt"));
  const auto [scaled_left, scaled_right] = left_and_right(testing::render_scene(*scaled, "local"));
  EXPECT_EQ(scaled_left, 0);
  EXPECT_GT(scaled_right, 0);

  // The same camera as a matrix (pbrt's column order): the general path gives the plain LookAt's image.
  const auto matrix = load_scene_file(
      write("Transform [-1 0 0 0  0 1 0 0  0 0 -1 0  0 0 5 1]\n" + film + world, "matrix.pbrt"));
  const auto [matrix_left, matrix_right] = left_and_right(testing::render_scene(*matrix, "local"));
  EXPECT_NEAR(matrix_left, plain_left, 1e-9 * plain_left);
  EXPECT_EQ(matrix_right, 0);
}

TEST_F(PbrtScene, SyntaxErrorsAreLocated) {
  InputError e = error_of(kView + "Shape \"sphere\" \"float radius\" [1\n");
  EXPECT_EQ(e.location().line, 5);
  EXPECT_EQ(e.location().column, 31);
  EXPECT_NE(e.message().find("unbalanced ["), std::string::npos) << e.what();

  e = error_of(kView + "Shape \"sphere\n");
  EXPECT_EQ(e.location().line, 5);
  EXPECT_EQ(e.location().column, 7);
  EXPECT_NE(e.message().find("unterminated string"), std::string::npos) << e.what();

  e = error_of(kView + "Shape \"sphere\" \"float radius\" [1.2.3]\n");
  EXPECT_EQ(e.location().line, 5);
  EXPECT_EQ(e.location().column, 32);
  EXPECT_NE(e.message().find("bad number '1.2.3'"), std::string::npos) << e.what();

  e = error_of(kView + "Translate 1 2 1e999\n");
  EXPECT_NE(e.message().find("bad number"), std::string::npos) << e.what();

  e = error_of(kView + "Shape \"sphere\" \"float radius\" 1 ]\n");
  EXPECT_EQ(e.location().column, 33);
  EXPECT_NE(e.message().find("unbalanced ]"), std::string::npos) << e.what();

  e = error_of(kView + "AttributeBegin\nAttributeEnd\n  AttributeEnd\n");
  EXPECT_EQ(e.location().line, 7);
  EXPECT_EQ(e.location().column, 3);
  EXPECT_NE(e.message().find("AttributeEnd without AttributeBegin"), std::string::npos) << e.what();

  e = error_of(kView + "Shape \"sphere\" \"float radius\" \"big\"\n");
  EXPECT_NE(e.message().find("takes numbers"), std::string::npos) << e.what();
  EXPECT_EQ(e.location().file, (directory_.path() / "scene.pbrt").string());
}

TEST_F(PbrtScene, IncludesAreRelativeAndACycleIsAnError) {
  std::filesystem::create_directories(directory_.path() / "parts");
  write("Shape \"sphere\"\n", "parts/ball.pbrt");
  const PbrtSceneDocument included = pbrt_scene_document(write(kView + "Include \"parts/ball.pbrt\"\n"));
  ASSERT_EQ(included.document["shapes"].size(), 1u);
  EXPECT_EQ(included.document["shapes"][0]["type"], "sphere");

  // a.pbrt → parts/b.pbrt → ../a.pbrt: the error is at the Include that closes the cycle.
  write("Include \"../a.pbrt\"\n", "parts/b.pbrt");
  const InputError cycle = error_of(kView + "Include \"parts/b.pbrt\"\n", "a.pbrt");
  EXPECT_NE(cycle.message().find("recursive Include"), std::string::npos) << cycle.what();
  EXPECT_NE(cycle.message().find("a.pbrt → "), std::string::npos) << cycle.what();
  EXPECT_NE(cycle.message().find("b.pbrt → "), std::string::npos) << cycle.what();
  EXPECT_NE(cycle.location().file.find("b.pbrt"), std::string::npos);
  EXPECT_EQ(cycle.location().line, 1);

  const InputError missing = error_of(kView + "\n  Include \"nowhere.pbrt\"\n");
  EXPECT_EQ(missing.location().line, 6);
  EXPECT_EQ(missing.location().column, 3);
  EXPECT_NE(missing.message().find("nowhere.pbrt"), std::string::npos) << missing.what();
}

TEST_F(PbrtScene, WhatCandelaDoesNotDrawIsAWarningAtFileAndLine) {
  const std::vector<std::string> warnings =
      warnings_of(kView + R"(MakeNamedMedium "fog" "string type" "homogeneous"
Frobnicate 1 2 "x" [3]
Shape "teapot" "float size" [2]
Material "hair"
Shape "sphere"
)");
  EXPECT_TRUE(any_contains(warnings, "scene.pbrt:5: MakeNamedMedium is not used"));
  EXPECT_TRUE(any_contains(warnings, "scene.pbrt:6: unknown directive \"Frobnicate\""));
  EXPECT_TRUE(any_contains(warnings, "scene.pbrt:7: unknown shape type \"teapot\""));
  EXPECT_TRUE(any_contains(warnings, "scene.pbrt:8: unknown material type \"hair\""));
  // The scene after them is read: the sphere, of the grey the unknown material became.
  const PbrtSceneDocument translated =
      pbrt_scene_document(write(kView + "Frobnicate\nMaterial \"hair\"\nShape \"sphere\"\n"));
  ASSERT_EQ(translated.document["shapes"].size(), 1u);
  EXPECT_EQ(translated.document["materials"]["material-1"]["kd"], 0.5);
}

}  // namespace
}  // namespace candela
