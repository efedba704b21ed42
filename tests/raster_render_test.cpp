// The raster method (issue 6, SPEC §9, 000 §3) against the ray tracer and the seed's
// descriptions of flat, Gouraud, Phong and dot-product shading.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <set>
#include <tuple>

#include "integrators/method_registry.h"
#include "scene/scene_loader.h"
#include "util/error.h"

namespace candela {
namespace {

std::unique_ptr<Scene> scene_from(const std::string& body, const std::vector<std::string>& overrides = {}) {
  return load_scene_text(R"({"format": "candela/1", )" + body + "}", "raster.json", ".", overrides);
}

Film render(const Scene& scene, const std::string& method_name, std::size_t threads = 2) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  const auto method = find_method(method_name)->create();
  Film film(scene.camera->width(), scene.camera->height());
  RunStatistics statistics;
  method->render(scene, {{0, 0, film.width(), film.height()}, true}, film, statistics);
  return film;
}

double difference(const Color& a, const Color& b) {
  return std::max({std::fabs(a.r - b.r), std::fabs(a.g - b.g), std::fabs(a.b - b.b)});
}

const char* kSphereScene = R"(
  "camera": {"eye": [0, 0, 5], "target": [0, 0, 0], "fov": 40, "width": 64, "height": 64},
  "background": [0, 0, 0.5], "ambient": 0.1,
  "lights": [{"type": "point", "position": [3, 4, 5]}, {"type": "directional", "direction": [1, 0, -1], "intensity": 0.3}],
  "materials": {"m": {"kd": [0.7, 0.4, 0.2], "ks": 0.5, "n": 20}},
  "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1.2, "material": "m"}],
  "local": {"shadows": false})";

TEST(RasterRender, PhongOnAFineSphereMatchesTheRayTracedLocalModel) {
  const auto scene = scene_from(kSphereScene, {"raster.segments=256", "raster.shading=\"phong\""});
  const Film raster = render(*scene, "raster");
  const Film traced = render(*scene, "local");
  int covered = 0, far_off = 0;
  double total = 0;
  for (int y = 0; y < raster.height(); ++y)
    for (int x = 0; x < raster.width(); ++x) {
      const bool raster_background = raster.at(x, y) == Color(0, 0, 0.5);
      const bool traced_background = traced.at(x, y) == Color(0, 0, 0.5);
      if (raster_background != traced_background) {
        ++far_off;  // only on the silhouette: the polygon lies inside the sphere
        continue;
      }
      if (raster_background) continue;
      ++covered;
      const double d = difference(raster.at(x, y), traced.at(x, y));
      total += d;
      EXPECT_LT(d, 0.02) << x << "," << y;
    }
  EXPECT_GT(covered, 1000);
  EXPECT_LT(total / covered, 2e-3);
  EXPECT_LT(far_off, 40);
}

TEST(RasterRender, FlatShadingIsConstantPerTriangle) {
  // A coarse sphere: flat shading shows at most one colour per triangle, Gouraud many more.
  const auto flat = scene_from(kSphereScene, {"raster.segments=8", "raster.shading=\"flat\""});
  const auto gouraud = scene_from(kSphereScene, {"raster.segments=8", "raster.shading=\"gouraud\""});
  const auto colours = [](const Film& film) {
    std::set<std::tuple<double, double, double>> distinct;
    for (const Color& c : film.pixels()) distinct.insert({c.r, c.g, c.b});
    return distinct.size();
  };
  // 8 longitudes × 4 latitudes: at most 8·4·2 triangles (fewer at the poles), plus background.
  EXPECT_LE(colours(render(*flat, "raster")), 8u * 4u * 2u + 1u);
  EXPECT_GT(colours(render(*gouraud, "raster")), 500u);
}

TEST(RasterRender, GouraudLosesAHighlightInsideAPolygonPhongKeepsIt) {
  // 000 §3.2.1: one big square under a light right above its centre, a tight highlight. Gouraud
  // interpolates the four corner intensities and never exceeds them; Phong evaluates the model
  // at the centre and shows the highlight.
  const std::string body = R"(
    "camera": {"eye": [0, 0, 4], "target": [0, 0, 0], "fov": 60, "width": 48, "height": 48},
    "lights": [{"type": "point", "position": [0, 0, 1]}],
    "materials": {"m": {"kd": 0.2, "ks": 1, "n": 50}},
    "shapes": [{"type": "quad", "corner": [-1, -1, 0], "edge_u": [2, 0, 0], "edge_v": [0, 2, 0], "material": "m"}])";
  const auto gouraud = scene_from(body, {"raster.shading=\"gouraud\""});
  const auto phong = scene_from(body, {"raster.shading=\"phong\""});
  const auto brightest = [](const Film& film) {
    double best = 0;
    for (const Color& c : film.pixels()) best = std::max(best, c.r);
    return best;
  };
  // At a corner: N·L = 1/√3 and R·V = 2/√54 ≈ 0.27, so I ≈ 0.2/√3 + 0.27^50 ≈ 0.115.
  const double gouraud_peak = brightest(render(*gouraud, "raster"));
  const double phong_peak = brightest(render(*phong, "raster"));
  EXPECT_NEAR(gouraud_peak, 0.2 / std::sqrt(3.0), 0.01);  // nothing brighter than the corners
  EXPECT_GT(phong_peak, 1.0);    // kd + ks at the centre: 1.2
}

TEST(RasterRender, EveryModeEqualsTheRayTracerOnALitPlane) {
  // A directional light on a plane: N·L is constant and R·V is linear enough to make every mode
  // agree with ray casting to within interpolation error; the diffuse-only case exactly.
  const std::string body = R"(
    "camera": {"eye": [0.3, 0.2, 3], "target": [0, 0, 0], "fov": 50, "width": 40, "height": 30},
    "ambient": 0.2, "background": [1, 0, 1],
    "lights": [{"type": "directional", "direction": [-0.3, -0.2, -1], "intensity": 0.8}],
    "materials": {"m": {"kd": {"type": "checker2d", "even": [0.8, 0.6, 0.2], "odd": [0.2, 0.3, 0.6], "mapping": {"type": "uv", "scale": 4}}}},
    "shapes": [{"type": "quad", "corner": [-1, -1, 0], "edge_u": [2, 0, 0], "edge_v": [0, 2, 0], "material": "m"}],
    "local": {"shadows": false})";
  const auto scene = scene_from(body);
  const Film traced = render(*scene, "local");
  for (const char* shading : {"flat", "gouraud", "phong", "dotproduct"}) {
    const auto raster_scene = scene_from(body, {std::string("raster.shading=\"") + shading + "\""});
    const Film raster = render(*raster_scene, "raster");
    int mismatched = 0;
    for (int y = 0; y < traced.height(); ++y)
      for (int x = 0; x < traced.width(); ++x)
        if (difference(raster.at(x, y), traced.at(x, y)) > 1e-9) ++mismatched;
    // Flat and Gouraud evaluate the texture at the centroid or the corners, not per pixel.
    if (std::string(shading) == "phong" || std::string(shading) == "dotproduct")
      EXPECT_LE(mismatched, 6) << shading;  // pixels whose centre lies exactly on a checker edge
    else
      EXPECT_GT(mismatched, 0) << shading;
  }
}

TEST(RasterRender, SameBytesWhateverTheThreadCount) {
  for (const char* shading : {"flat", "gouraud", "phong", "dotproduct"}) {
    const auto scene = load_default_scene({"camera.width=64", "camera.height=48", std::string("raster.shading=\"") + shading + "\""});
    const Film one = render(*scene, "raster", 1);
    const Film two = render(*scene, "raster", 2);
    ASSERT_EQ(one.pixels().size(), two.pixels().size());
    for (std::size_t i = 0; i < one.pixels().size(); ++i) ASSERT_TRUE(one.pixels()[i] == two.pixels()[i]) << shading << " " << i;
  }
}

TEST(RasterRender, SettingsAreChecked) {
  EXPECT_THROW(scene_from(kSphereScene, {"raster.shading=\"toon\""}), InputError);
  EXPECT_THROW(scene_from(kSphereScene, {"raster.segments=2"}), InputError);
  EXPECT_THROW(scene_from(kSphereScene, {"raster.crease_angle=200"}), InputError);
  // Dot-product shading carries four values per light: too many lights is a clear error.
  std::string lights = R"("lights": [)";
  for (int i = 0; i < 20; ++i) lights += std::string(i ? ", " : "") + R"({"type": "point", "position": [0, 5, 5]})";
  const auto crowded = scene_from(R"("camera": {"width": 8, "height": 8}, )" + lights +
                                  R"(], "shapes": [{"type": "sphere"}], "raster": {"shading": "dotproduct"})");
  try {
    render(*crowded, "raster");
    FAIL() << "expected an error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("at most"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace candela
