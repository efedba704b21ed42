// Issue 20: "flip_normals" on any shape, seen by every method (geometry/flipped_shape.h).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "integrators/scene_loading.h"
#include "render_support.h"
#include "util/error.h"

namespace candela {
namespace {

std::string sphere_room(const std::string& method, const std::string& settings, bool flipped,
                        const std::string& material) {
  return R"({"format": "candela/1",
    "camera": {"eye": [0.1, 0.2, 0], "target": [0, 0, -1], "fov": 70, "width": 16, "height": 16},
    "render": {"method": ")" +
         method + R"("}, )" + settings + R"(
    "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 2, "flip_normals": )" +
         (flipped ? "true" : "false") + R"(, "material": )" + material + "}]}";
}

// Classic radiosity's patches are one-sided: from inside a sphere it saw only their backs and
// drew the emission alone (1 where E/(1 − ρ) = 3.33). Flipped, the sphere is a furnace for it
// too — the inside of an analytic shape, hemicube and ray cast.
TEST(FlipNormals, RadiosityModelsTheInsideOfASphere) {
  for (const std::string form_factors : {"hemicube", "ray-cast"})
    for (const bool flipped : {false, true}) {
      const auto scene = load_scene_text(
          sphere_room("radiosity",
                      R"("radiosity": {"solver": "gauss-seidel", "threshold": 1e-7, "form_factors": ")" +
                          form_factors + R"("},)",
                      flipped, R"({"kd": [0.5, 0.7, 0.8], "emission": 1})"),
          "sphere.json", ".");
      const Film film = testing::render_scene(*scene, "radiosity");
      const double expected = flipped ? 1 / 0.3 : 1.0;
      for (const Color& pixel : film.pixels())
        ASSERT_NEAR(pixel.g, expected, 0.01 * expected) << form_factors << (flipped ? ", flipped" : "");
    }
}

// The methods whose surfaces are two-sided (local, Whitted, raster, meshless, path: normals turned
// toward the viewer) draw an opaque diffuse scene the same flipped or not: a lamp-lit sphere and
// floor, the sphere flipped.
TEST(FlipNormals, TwoSidedMethodsDrawTheSameImage) {
  const auto scene_text = [](const std::string& method, bool flipped) {
    return std::string(R"({"format": "candela/1",
      "camera": {"eye": [0, 1, 5], "target": [0, 0.5, 0], "fov": 50, "width": 24, "height": 24},
      "render": {"method": ")") +
           method + R"("}, "path": {"spp": 64}, "meshless": {"spacing": 0.4, "grid": 16, "rounds": 2},
      "lights": [{"type": "point", "position": [2, 4, 3], "intensity": 400, "attenuation": "inverse-square"}],
      "shapes": [{"type": "sphere", "center": [0, 0.8, 0], "radius": 0.8, "flip_normals": )" +
           (flipped ? "true" : "false") + R"(, "material": {"kd": [0.7, 0.3, 0.2]}},
                 {"type": "quad", "corner": [-3, 0, 3], "edge_u": [6, 0, 0], "edge_v": [0, 0, -6], "material": {"kd": 0.6}}]})";
  };
  for (const std::string method : {"local", "whitted", "raster", "meshless", "path"}) {
    const Film plain =
        testing::render_scene(*load_scene_text(scene_text(method, false), "s.json", "."), method);
    const Film flipped =
        testing::render_scene(*load_scene_text(scene_text(method, true), "s.json", "."), method);
    double largest = 0, brightest = 0, plain_sum = 0, flipped_sum = 0;
    for (std::size_t i = 0; i < plain.pixels().size(); ++i) {
      largest = std::max(largest, std::fabs(plain.pixels()[i].r - flipped.pixels()[i].r));
      brightest = std::max(brightest, plain.pixels()[i].r);
      plain_sum += plain.pixels()[i].r;
      flipped_sum += flipped.pixels()[i].r;
    }
    EXPECT_GT(brightest, 0.05) << method;
    if (method == "path")  // the same estimate in the mean; its samples' frames differ (other noise)
      EXPECT_NEAR(flipped_sum / plain_sum, 1, 0.03) << method;
    else
      EXPECT_LE(largest, 1e-9 * brightest) << method;
  }
}

// A dielectric is entered from the side its normal faces: a glass ball flipped is a ball of
// air in glass (the index seen the other way), and refracts differently.
TEST(FlipNormals, ADielectricIsEnteredFromTheOtherSide) {
  const auto scene_text = [](bool flipped) {
    return std::string(R"({"format": "candela/1",
      "camera": {"eye": [0, 0, 4], "target": [0, 0, 0], "fov": 40, "width": 24, "height": 24},
      "render": {"method": "whitted"}, "ambient": 0.2,
      "lights": [{"type": "point", "position": [0, 3, 4]}],
      "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "flip_normals": )") +
           (flipped ? "true" : "false") + R"(,
                  "material": {"kd": 0, "ks": 0.1, "kt": 0.9, "ior": 1.5}},
                 {"type": "quad", "corner": [-4, -4, -2], "edge_u": [8, 0, 0], "edge_v": [0, 8, 0],
                  "material": {"kd": {"type": "checkerboard", "even": 0.9, "odd": 0.1, "size": 0.5}}}]})";
  };
  const Film plain = testing::render_scene(*load_scene_text(scene_text(false), "g.json", "."), "whitted");
  const Film flipped = testing::render_scene(*load_scene_text(scene_text(true), "g.json", "."), "whitted");
  double difference = 0;
  for (std::size_t i = 0; i < plain.pixels().size(); ++i)
    difference += std::fabs(plain.pixels()[i].g - flipped.pixels()[i].g);
  EXPECT_GT(difference / static_cast<double>(plain.pixels().size()), 0.01);
}

TEST(FlipNormals, ANonBooleanIsRefusedWithItsPlace) {
  try {
    load_scene_text(
        sphere_room("local", "", false, R"({"kd": 0.5})")
            .replace(sphere_room("local", "", false, R"({"kd": 0.5})").find("false"), 5, "\"yes\""),
        "bad.json", ".");
    FAIL() << "accepted";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("flip_normals"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace candela
