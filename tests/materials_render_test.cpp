// End to end: materials, textures, environment maps, bump mapping and the see-through
// transparency models inside whole renders (SPEC §7, 000 §4).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include "integrators/local.h"
#include "integrators/method_registry.h"
#include "integrators/scene_loading.h"
#include "integrators/whitted.h"
#include "io/image_writer.h"
#include "render_support.h"
#include "scene_text.h"
#include "scratch_directory.h"
#include "shading/fresnel.h"

namespace candela {
namespace {

namespace fs = std::filesystem;

using testing::kCentreCamera;
using testing::scene_from;

Color pixel(const Scene& scene) {
  Color radiance;
  WhittedMethod().pixel_ray_tree(scene, 0, 0, radiance);
  return radiance;
}

Film whitted_image(const Scene& scene) {
  return testing::render_scene(scene, "whitted");
}

void expect_color_near(const Color& got, const Color& expected, double tolerance) {
  EXPECT_NEAR(got.r, expected.r, tolerance);
  EXPECT_NEAR(got.g, expected.g, tolerance);
  EXPECT_NEAR(got.b, expected.b, tolerance);
}

TEST(MaterialsRender, BumpLeavesTheSilhouetteSmooth) {
  // 000 §4.2.1: the bump changes shading, never the outline. Every pixel that shows the
  // background without the bump shows it with the bump, and the other way round.
  const std::string camera =
      R"({"eye": [0, 0, 6], "target": [0, 0, 0], "fov": 40, "width": 48, "height": 48})";
  const std::string lights =
      R"("lights": [{"type": "point", "position": [3, 4, 6]}], "background": [0, 0, 1], )";
  const auto plain = scene_from(
      lights +
          R"("shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1.5, "material": {"kd": [1, 1, 0], "ks": 0.3}}])",
      camera);
  const auto bumped = scene_from(
      lights +
          R"("shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1.5, "material": {"kd": [1, 1, 0], "ks": 0.3,
      "bump": {"height": {"type": "waves", "waves": [{"amplitude": 1, "frequency": [24, 0]}, {"amplitude": 0.5, "frequency": [0, 12]}]}, "scale": 0.004}}}])",
      camera);
  const Film a = whitted_image(*plain);
  const Film b = whitted_image(*bumped);
  int background = 0, different = 0;
  for (int y = 0; y < a.height(); ++y)
    for (int x = 0; x < a.width(); ++x) {
      const bool a_background = a.at(x, y) == Color(0, 0, 1);
      const bool b_background = b.at(x, y) == Color(0, 0, 1);
      EXPECT_EQ(a_background, b_background) << x << "," << y;
      background += a_background;
      if (!a_background && !(a.at(x, y) == b.at(x, y))) ++different;
    }
  EXPECT_GT(background, 500);
  EXPECT_GT(different, 500);  // and yet the surface inside is visibly bumped
}

TEST(MaterialsRender, ConstantTransparencyBlendsFrontAndBehind) {
  // 000 §4.4: I = (1 − t)·I_front + t·I_behind, the ray going on undeviated.
  const std::string back =
      R"({"type": "plane", "point": [0, 0, -2], "normal": [0, 0, 1], "material": {"kd": [1, 0, 0]}})";
  const std::string light = R"("lights": [{"type": "directional", "direction": [0, 0, -1]}], )";
  const auto front_only = scene_from(
      light +
          R"("shapes": [{"type": "plane", "point": [0, 0, 0], "normal": [0, 0, 1], "material": {"kd": [0, 0.5, 0]}}])",
      kCentreCamera);
  const auto behind_only = scene_from(light + R"("shapes": [)" + back + "]", kCentreCamera);
  const auto both =
      scene_from(light + R"("shapes": [{"type": "plane", "point": [0, 0, 0], "normal": [0, 0, 1],
      "material": {"kd": [0, 0.5, 0], "transparency": {"model": "constant", "t": 0.3}}}, )" +
                     back + "]",
                 kCentreCamera);
  const Color front = pixel(*front_only);
  // The back plane is lit through the pane: its light is attenuated by t on the way in.
  const Color behind = pixel(*behind_only) * 0.3;
  expect_color_near(pixel(*both), front * 0.7 + behind * 0.3, 1e-12);
  // The blend belongs to the local model (000 §4.4): ray casting shows it too.
  Color local;
  LocalMethod().pixel_ray_tree(*both, 0, 0, local);
  expect_color_near(local, front * 0.7 + behind * 0.3, 1e-12);
}

TEST(MaterialsRender, ThinSheetsPassTheirTransmittanceAtEachCrossingWithoutBending) {
  // A thin sheet (a pane, kt its transmissivity) lets its transmittance T(θ)
  // (shading/fresnel.h) through each time a ray crosses it, and does not bend it. The floor is
  // seen through a thin box (two crossings at normal incidence) in the camera ray and in the
  // shadow ray: T(0°)⁴ of its unglazed value; a tilted pane, not bent, the floor's point ahead.
  const std::string back =
      R"({"type": "plane", "point": [0, 0, -2], "normal": [0, 0, 1], "material": {"kd": [1, 0, 0]}})";
  const std::string light = R"("lights": [{"type": "directional", "direction": [0, 0, -1]}], )";
  const std::string thin = R"("material": {"kd": 0, "kt": 0.5, "ior": 1.5, "thin": true})";
  const Color behind = pixel(*scene_from(light + R"("shapes": [)" + back + "]", kCentreCamera));
  ASSERT_GT(behind.r, 0.1);
  const auto boxed =
      scene_from(light + R"("shapes": [{"type": "box", "min": [-1, -1, -0.5], "max": [1, 1, 0.5], )" + thin +
                     "}, " + back + "]",
                 kCentreCamera);
  const double normal = thin_sheet(1, 1.5, 0.5).transmittance;
  EXPECT_NEAR(normal, 0.96 * 0.96 * 0.5 / (1 - 0.04 * 0.04 * 0.25), 1e-15);
  expect_color_near(pixel(*boxed), behind * std::pow(normal, 4), 1e-12);
  // A pane tilted by 60°, crossed once by the camera ray and once by the light's: under a narrow
  // spot (a lit disc of radius 0.35 on the floor) a bent camera ray, 25° off, would land in the dark.
  const std::string spot =
      R"("lights": [{"type": "spot", "position": [0, 0, 8], "target": [0, 0, -2], "cutoff": 2, "falloff_start": 1}], )";
  const auto tilted = scene_from(
      spot + R"("shapes": [{"type": "plane", "point": [0, 0, 0], "normal": [0.8660254037844386, 0, 0.5], )" +
          thin + "}, " + back + "]",
      kCentreCamera);
  const Color spot_behind = pixel(*scene_from(spot + R"("shapes": [)" + back + "]", kCentreCamera));
  ASSERT_GT(spot_behind.r, 0.01);
  const double slanted = thin_sheet(0.5, 1.5, 0.5).transmittance;  // both rays 60° off the pane's normal
  EXPECT_LT(slanted, 0.8 * normal);
  expect_color_near(pixel(*tilted), spot_behind * slanted * slanted, 1e-9);
}

TEST(MaterialsRender, LinearAndNonlinearTransparencyFollowTheNormal) {
  // A sphere seen through its centre has n_z = 1 at both surfaces: t = t_max there; the
  // same in the nonlinear model (1 − (1 − 1)^m = 1).
  const std::string light = R"("ambient": 1, )";
  const auto expect_through_centre = [&](const std::string& transparency, double t) {
    const auto scene = scene_from(
        light + R"("background": [0, 0, 1], "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1,
        "material": {"kd": [1, 0, 0], "transparency": )" +
            transparency + "}}]",
        kCentreCamera);
    // Two surfaces, each I = (1 − t)·kd·Ia + t·(what lies behind).
    const Color inner = Color(1, 0, 0) * (1 - t) + Color(0, 0, 1) * t;
    const Color outer = Color(1, 0, 0) * (1 - t) + inner * t;
    expect_color_near(pixel(*scene), outer, 1e-12);
  };
  expect_through_centre(R"({"model": "linear", "t_min": 0.1, "t_max": 0.8})", 0.8);
  expect_through_centre(R"({"model": "nonlinear", "t_min": 0.1, "t_max": 0.6, "m": 3})", 0.6);
  // Off centre, seen along −x: n_z is |N·V| at the hit (not the world z of the normal, which
  // is 0 here). A chord of a sphere meets both surfaces at the same |N·V|.
  const Vec3 eye{10, 0, 0};
  const Vec3 direction = normalize(Vec3{0, 0.6, 0} - eye);
  const double b = dot(eye, direction);
  const double distance = -b - std::sqrt(b * b - (dot(eye, eye) - 1));
  const double n_z = std::fabs(dot(eye + direction * distance, direction));  // N = p on the unit sphere
  const auto expect_off_centre = [&](const std::string& transparency, double t) {
    const auto scene = scene_from(
        light + R"("background": [0, 0, 1], "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1,
        "material": {"kd": [1, 0, 0], "transparency": )" +
            transparency + "}}]",
        R"({"eye": [10, 0, 0], "target": [0, 0.6, 0], "fov": 1, "width": 1, "height": 1})");
    const Color inner = Color(1, 0, 0) * (1 - t) + Color(0, 0, 1) * t;
    // The see-through ray starts 1e-7·extent inside: its second hit moves by as much.
    expect_color_near(pixel(*scene), Color(1, 0, 0) * (1 - t) + inner * t, 1e-6);
  };
  expect_off_centre(R"({"model": "linear", "t_min": 0.1, "t_max": 0.8})", 0.1 + 0.7 * n_z);
  expect_off_centre(R"({"model": "nonlinear", "t_min": 0.1, "t_max": 0.8, "m": 3})",
                    0.1 + 0.7 * (1 - std::pow(1 - n_z, 3)));
  // Off centre n_z < 1: the linear model is less transparent there.
  Transparency linear;
  linear.model = TransparencyModel::linear;
  linear.t_min = 0.1;
  linear.t_max = 0.8;
  EXPECT_NEAR(linear.at(0.5), 0.45, 1e-15);
  EXPECT_NEAR(linear.at(0), 0.1, 1e-15);
  Transparency nonlinear = linear;
  nonlinear.model = TransparencyModel::nonlinear;
  nonlinear.exponent = 2;
  EXPECT_NEAR(nonlinear.at(0.5), 0.1 + 0.7 * 0.75, 1e-15);
  EXPECT_GT(nonlinear.at(0.5), linear.at(0.5));  // more transparent away from the silhouette
}

TEST(MaterialsRender, TexturedKrReflectsOnlyWhereTheTextureSaysSo) {
  // kr from a 2D checker over the plane's uv (uv = the hit's coordinates): the centre pixel
  // sees cell (0, 0) — even, kr = 0.5 — of a mirror facing a white background.
  const auto scene =
      scene_from(R"("background": 1, "shapes": [{"type": "plane", "point": [0, 0, 0], "normal": [0, 0, 1],
      "material": {"kd": 0, "kr": {"type": "checker2d", "even": 0.5, "odd": 0, "mapping": {"type": "uv", "offset": [0.5, 0.5]}}}}])",
                 kCentreCamera);
  expect_color_near(pixel(*scene), Color(0.5), 1e-12);
  const auto shifted =
      scene_from(R"("background": 1, "shapes": [{"type": "plane", "point": [0, 0, 0], "normal": [0, 0, 1],
      "material": {"kd": 0, "kr": {"type": "checker2d", "even": 0.5, "odd": 0, "mapping": {"type": "uv", "offset": [1.5, 0.5]}}}}])",
                 kCentreCamera);
  expect_color_near(pixel(*shifted), Color(0), 1e-12);
}

TEST(MaterialsRender, NegativeTextureValuesNeverMakeNegativePixels) {
  // Waves swing to −1: as kd they would give negative light; reflectances stay >= 0.
  const std::string camera =
      R"({"eye": [0, 0, 6], "target": [0, 0, 0], "fov": 40, "width": 24, "height": 24})";
  const auto scene = scene_from(
      R"("ambient": 0.5, "lights": [{"type": "point", "position": [2, 3, 5]}], "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1.5,
      "material": {"kd": {"type": "waves", "waves": [{"amplitude": 1, "frequency": [8, 0]}]}, "ks": {"type": "noise", "amplitude": 4, "offset": -2}}}])",
      camera);
  const Film film = whitted_image(*scene);
  int dark = 0;
  for (const Color& c : film.pixels()) {
    EXPECT_TRUE(c.r >= 0 && c.g >= 0 && c.b >= 0) << c.r << " " << c.g << " " << c.b;
    dark += c.is_black();
  }
  EXPECT_GT(dark, 0);  // where the waves are negative the surface is black, not negative
}

TEST(MaterialsRender, EveryParameterTakesATexture) {
  // ka, kd, ks, n, kr, kt, ior (and roughness) each from a texture: a 2D checker over the
  // plane's uv, even cells one value, odd cells another.
  const auto checker = [](const std::string& even, const std::string& odd) {
    return R"({"type": "checker2d", "even": )" + even + R"(, "odd": )" + odd + "}";
  };
  const auto scene =
      scene_from(R"("shapes": [{"type": "plane", "point": [0, 0, 0], "normal": [0, 0, 1], "material": {
      "ka": )" + checker("[0.1, 0.2, 0.3]", "0") +
                     R"(, "kd": )" + checker("[0.4, 0.5, 0.6]", "0") + R"(, "ks": )" + checker("0.7", "0") +
                     R"(, "n": )" + checker("33", "1") + R"(, "kr": )" + checker("0.25", "0") +
                     R"(, "kt": )" + checker("0.5", "0") + R"(, "ior": )" + checker("1.7", "1") + "}}]",
                 kCentreCamera);
  const Material& material = scene->materials.back();
  SurfaceHit even, odd;
  even.uv = {0.5, 0.5};
  odd.uv = {1.5, 0.5};
  const SurfaceProperties a = material.at(even), b = material.at(odd);
  expect_color_near(a.ka, Color(0.1, 0.2, 0.3), 1e-15);
  expect_color_near(a.kd, Color(0.4, 0.5, 0.6), 1e-15);
  EXPECT_NEAR(a.ks, 0.7, 1e-15);
  EXPECT_NEAR(a.shininess, 33, 1e-12);
  EXPECT_NEAR(a.kr, 0.25, 1e-15);
  EXPECT_NEAR(a.kt, 0.5, 1e-15);
  EXPECT_NEAR(a.ior, 1.7, 1e-15);
  EXPECT_TRUE(b.ka.is_black());
  EXPECT_EQ(b.ks, 0.0);
  EXPECT_NEAR(b.shininess, 1, 1e-15);
  EXPECT_EQ(b.kr, 0.0);
  EXPECT_NEAR(b.ior, 1.0, 1e-15);
  EXPECT_TRUE(material.has_reflection());
  EXPECT_TRUE(material.has_refraction());
  const auto rough =
      scene_from(R"("shapes": [{"type": "sphere", "material": {"type": "cook-torrance", "roughness": )" +
                     checker("0.2", "0.6") + "}}]",
                 kCentreCamera);
  EXPECT_NEAR(rough->materials.back().at(even).roughness, 0.2, 1e-15);
  EXPECT_NEAR(rough->materials.back().at(odd).roughness, 0.6, 1e-15);
}

TEST(MaterialsRender, ConstantTexturesAreRangeChecked) {
  const auto expect_error = [](const std::string& material, const std::string& expected) {
    try {
      scene_from(R"("shapes": [{"type": "sphere", "material": )" + material + "}]", kCentreCamera);
      FAIL() << "expected an error for " << material;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
    }
  };
  expect_error(R"({"type": "cook-torrance", "roughness": {"type": "constant", "value": 0}})",
               "shapes[0].material.roughness: must be > 0");
  expect_error(R"({"ior": {"type": "constant", "value": 0}})", "shapes[0].material.ior: must be > 0");
  expect_error(R"({"kr": {"type": "constant", "value": 1.5}})", "must be in [0, 1]");
  // A spherical mapping without a centre cannot carry bump heights (its uv never move).
  expect_error(
      R"({"bump": {"height": {"type": "waves", "waves": [{"frequency": [24, 0]}], "mapping": "spherical"}}})",
      "shapes[0].material.bump.height: a spherical mapping without \"center\"");
}

TEST(MaterialsRender, SecondaryRaysOfASeeThroughSurfaceCarryItsShare) {
  // kr 0.5 on a surface with t = 0.9: the reflection reaches the pixel with weight 0.1·0.5.
  const auto scene =
      scene_from(R"("background": 1, "shapes": [{"type": "plane", "point": [0, 0, 0], "normal": [0, 0, 1],
      "material": {"kd": 0, "kr": 0.5, "transparency": {"model": "constant", "t": 0.9}}}])",
                 kCentreCamera);
  Color radiance;
  const RayTree tree = WhittedMethod().pixel_ray_tree(*scene, 0, 0, radiance);
  bool found_reflection = false, found_see_through = false;
  for (const RayTreeNode& node : tree.nodes()) {
    if (node.kind == RayKind::reflected) {
      found_reflection = true;
      EXPECT_NEAR(node.weight, 0.05, 1e-15);
      EXPECT_NEAR(node.contribution.r, 0.05, 1e-15);  // background 1 × its weight
    }
    if (node.kind == RayKind::see_through) {
      found_see_through = true;
      EXPECT_NEAR(node.weight, 0.9, 1e-15);
    }
  }
  EXPECT_TRUE(found_reflection);
  EXPECT_TRUE(found_see_through);
  EXPECT_NEAR(radiance.r, 0.1 * 0.5 + 0.9, 1e-12);
}

class EnvironmentRender : public ::testing::Test {
 protected:
  void SetUp() override {
    // Six 2×2 faces (PFM: linear floats), each one flat color: face i has red = 0.1·(i + 1).
    const char* names[6] = {"px", "nx", "py", "ny", "pz", "nz"};
    for (int i = 0; i < 6; ++i) {
      Film face(2, 2);
      for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 2; ++x) face.at(x, y) = Color(red_of_face(i), 0.25, 0);
      write_pfm(face, (directory_ / (std::string(names[i]) + ".pfm")).string(), 0);
    }
  }
  static double red_of_face(int face) { return 0.125 * (face + 1); }
  candela::testing::ScratchDirectory scratch_{"candela-materials-render"};
  const fs::path& directory_ = scratch_.path();
};

const char* kCube =
    R"("environment": {"type": "cube", "faces": {"+x": "px.pfm", "-x": "nx.pfm", "+y": "py.pfm", "-y": "ny.pfm", "+z": "pz.pfm", "-z": "nz.pfm"}}, )";

TEST_F(EnvironmentRender, BackgroundIsTheCubeFaceAhead) {
  // Looking down −z: the −z face (index 5).
  const auto scene = scene_from(kCube + std::string(R"("shapes": [])"), kCentreCamera, directory_.string());
  EXPECT_NEAR(pixel(*scene).r, red_of_face(5), 1e-6);
  EXPECT_NEAR(pixel(*scene).g, 0.25, 1e-6);
}

TEST_F(EnvironmentRender, MirrorReflectsTheFaceBehindTheCamera) {
  // A mirror facing +z sends the central ray back along +z: the +z face (index 4).
  const auto scene = scene_from(
      kCube +
          std::string(
              R"("shapes": [{"type": "plane", "point": [0, 0, 0], "normal": [0, 0, 1], "material": {"kd": 0, "kr": 1}}])"),
      kCentreCamera, directory_.string());
  EXPECT_NEAR(pixel(*scene).r, red_of_face(4), 1e-6);
  // Turned 45° about x the mirror sends the ray up, to +y (index 2).
  const auto tilted = scene_from(
      kCube +
          std::string(
              R"("shapes": [{"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 1], "material": {"kd": 0, "kr": 1}}])"),
      kCentreCamera, directory_.string());
  EXPECT_NEAR(pixel(*tilted).r, red_of_face(2), 1e-6);
}

TEST_F(EnvironmentRender, RefractedRaysThatMissSeeTheEnvironment) {
  // A clear slab (kt = 1, ior 1.5) facing the eye: the ray passes straight through at normal
  // incidence and sees the −z face.
  const auto scene = scene_from(
      kCube +
          std::string(
              R"("shapes": [{"type": "box", "min": [-1, -1, -1], "max": [1, 1, 1], "material": {"kd": 0, "kt": 1, "ior": 1.5}}])"),
      kCentreCamera, directory_.string());
  EXPECT_NEAR(pixel(*scene).r, red_of_face(5), 1e-6);
}

TEST_F(EnvironmentRender, SixRendersFromTheCentreAreACubeMapOfTheScene) {
  // CubeLayout::inside: faces photographed by 90° cameras at the centre (up +y for the side
  // faces, −z looking up, +z looking down) give the same scene back as an environment. A
  // mirrored or rotated face convention would disagree on about half of the pixels.
  const std::string room = R"("ambient": 1, "shapes": [{"type": "box", "min": [-1, -1, -1], "max": [1, 1, 1],
      "material": {"kd": {"type": "checkerboard", "even": [0.9, 0.5, 0.1], "odd": [0.1, 0.3, 0.8], "size": 0.37, "offset": [0.11, 0.05, 0.02]}}},
      {"type": "sphere", "center": [0.6, 0.3, -0.5], "radius": 0.2, "material": {"kd": [1, 0, 0]}}])";
  const struct {
    const char* name;
    const char* forward;
    const char* up;
  } faces[6] = {{"px", "[1, 0, 0]", "[0, 1, 0]"},  {"nx", "[-1, 0, 0]", "[0, 1, 0]"},
                {"py", "[0, 1, 0]", "[0, 0, -1]"}, {"ny", "[0, -1, 0]", "[0, 0, 1]"},
                {"pz", "[0, 0, 1]", "[0, 1, 0]"},  {"nz", "[0, 0, -1]", "[0, 1, 0]"}};
  for (const auto& face : faces) {
    const auto scene =
        scene_from(room, std::string(R"({"eye": [0, 0, 0], "target": )") + face.forward + R"(, "up": )" +
                             face.up + R"(, "fov": 90, "width": 96, "height": 96})");
    write_pfm(whitted_image(*scene), (directory_ / (std::string("room-") + face.name + ".pfm")).string(), 0);
  }
  const std::string view =
      R"({"eye": [0, 0, 0], "target": [0.5, 0.35, -1], "up": [0.1, 1, 0], "fov": 100, "width": 48, "height": 40})";
  const Film direct = whitted_image(*scene_from(room, view));
  const Film through_cube = whitted_image(*scene_from(
      R"("environment": {"type": "cube", "faces": {"+x": "room-px.pfm", "-x": "room-nx.pfm", "+y": "room-py.pfm", "-y": "room-ny.pfm", "+z": "room-pz.pfm", "-z": "room-nz.pfm"}}, "shapes": [])",
      view, directory_.string()));
  int mismatched = 0;
  for (int y = 0; y < direct.height(); ++y)
    for (int x = 0; x < direct.width(); ++x) {
      const Color d = direct.at(x, y), c = through_cube.at(x, y);
      if (std::fabs(d.r - c.r) + std::fabs(d.g - c.g) + std::fabs(d.b - c.b) > 0.15) ++mismatched;
    }
  // Only pixels on cell and sphere edges differ (bilinear resampling of the faces).
  EXPECT_LT(mismatched, direct.width() * direct.height() / 10) << mismatched;
}

// Review findings on materials, textures and environment maps, each a test that failed before its fix.
TEST_F(EnvironmentRender, ScalarImagesAreLinearColorImagesSrgb) {
  // An 8-bit PNG holding 128 everywhere: as kr it is the number 128/255, as kd it is sRGB.
  Film grey(2, 2);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 2; ++x) grey.at(x, y) = Color(128 / 255.0);
  DisplaySettings linear_bytes;
  linear_bytes.srgb = false;
  write_png(grey, (directory_ / "grey.png").string(), linear_bytes);
  const auto mirror =
      scene_from(R"("background": 1, "shapes": [{"type": "plane", "point": [0, 0, 0], "normal": [0, 0, 1],
      "material": {"kd": 0, "kr": {"type": "image", "file": "grey.png"}}}])",
                 kCentreCamera, directory_.string());
  EXPECT_NEAR(pixel(*mirror).r, 128 / 255.0, 1e-6);
  const auto diffuse =
      scene_from(R"("ambient": 1, "shapes": [{"type": "plane", "point": [0, 0, 0], "normal": [0, 0, 1],
      "material": {"kd": {"type": "image", "file": "grey.png"}}}])",
                 kCentreCamera, directory_.string());
  EXPECT_NEAR(pixel(*diffuse).r, std::pow((128 / 255.0 + 0.055) / 1.055, 2.4), 1e-6);
}

TEST_F(EnvironmentRender, NonFiniteTexelsAreRefusedWithTheFileAndTexel) {
  Film bad(2, 1);
  bad.at(1, 0) = Color(1, std::numeric_limits<double>::infinity(), 0);
  write_pfm(bad, (directory_ / "bad.pfm").string(), 0);
  try {
    scene_from(R"("shapes": [{"type": "sphere", "material": {"kd": {"type": "image", "file": "bad.pfm"}}}])",
               kCentreCamera, directory_.string());
    FAIL() << "expected an error";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("bad.pfm"), std::string::npos) << message;
    EXPECT_NE(message.find("texel (1, 0)"), std::string::npos) << message;
    EXPECT_NE(message.find("infinite"), std::string::npos) << message;
  }
}

TEST_F(EnvironmentRender, ObjTextureCoordinatesAndMapKd) {
  // A unit quad with vt at its corners and an MTL whose map_Kd is a 2×2 image: the pixel aimed
  // at (−0.5, −0.5) has uv (0.25, 0.25), the centre of the bottom-left texel.
  Film texture(2, 2);  // film rows run top to bottom: (0, 1) is the bottom-left texel
  texture.at(0, 0) = Color(0, 1, 0);
  texture.at(1, 0) = Color(0, 0, 1);
  texture.at(0, 1) = Color(1, 0, 0);
  texture.at(1, 1) = Color(1, 1, 1);
  write_pfm(texture, (directory_ / "quad.pfm").string(), 0);
  {
    std::ofstream mtl(directory_ / "quad.mtl");
    mtl << "newmtl textured\nKd 0.5 0.5 0.5\nmap_Kd quad.pfm\n";
    std::ofstream obj(directory_ / "quad.obj");
    obj << "mtllib quad.mtl\nv -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\n"
           "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nusemtl textured\nf 1/1 2/2 3/3 4/4\n";
  }
  // Look straight down −z at a point: eye 10 units above it.
  const auto scene = scene_from(
      R"("lights": [{"type": "directional", "direction": [0, 0, -1]}], "shapes": [{"type": "mesh", "file": "quad.obj"}])",
      R"({"eye": [-0.5, -0.5, 10], "target": [-0.5, -0.5, 0], "fov": 1, "width": 1, "height": 1})",
      directory_.string());
  expect_color_near(pixel(*scene), Color(0.5, 0, 0), 1e-6);  // Kd × texel
  const auto top_right = scene_from(
      R"("lights": [{"type": "directional", "direction": [0, 0, -1]}], "shapes": [{"type": "mesh", "file": "quad.obj"}])",
      R"({"eye": [0.5, 0.5, 10], "target": [0.5, 0.5, 0], "fov": 1, "width": 1, "height": 1})",
      directory_.string());
  expect_color_near(pixel(*top_right), Color(0, 0, 0.5), 1e-6);
  // A missing map_Kd image is an error naming the OBJ's "file" entry.
  fs::remove(directory_ / "quad.pfm");
  try {
    scene_from(R"("shapes": [{"type": "mesh", "file": "quad.obj"}])", kCentreCamera, directory_.string());
    FAIL() << "expected an error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("shapes[0].file"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("map_Kd"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace candela
