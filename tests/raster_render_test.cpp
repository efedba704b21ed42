// The raster method (SPEC §9, 000 §3) against the ray tracer and the seed's
// descriptions of flat, Gouraud, Phong and dot-product shading.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <cstdio>
#include <set>
#include <tuple>

#include "integrators/method_registry.h"
#include "integrators/scene_loading.h"
#include "render_support.h"
#include "util/error.h"

namespace candela {
namespace {

std::unique_ptr<Scene> raster_scene(const std::string& body, const std::vector<std::string>& overrides = {}) {
  return load_scene_text(R"({"format": "candela/1", )" + body + "}", "raster.json", ".", overrides);
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
  const auto scene = raster_scene(kSphereScene, {"raster.segments=256", "raster.shading=\"phong\""});
  const Film raster = testing::render_scene(*scene, "raster");
  const Film traced = testing::render_scene(*scene, "local");
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
  // A coarse sphere: flat shading shows at most one color per triangle, Gouraud many more.
  const auto flat = raster_scene(kSphereScene, {"raster.segments=8", "raster.shading=\"flat\""});
  const auto gouraud = raster_scene(kSphereScene, {"raster.segments=8", "raster.shading=\"gouraud\""});
  const auto colors = [](const Film& film) {
    std::set<std::tuple<double, double, double>> distinct;
    for (const Color& c : film.pixels()) distinct.insert({c.r, c.g, c.b});
    return distinct.size();
  };
  // 8 longitudes × 4 latitudes: at most 8·4·2 triangles (fewer at the poles), plus background.
  EXPECT_LE(colors(testing::render_scene(*flat, "raster")), 8u * 4u * 2u + 1u);
  EXPECT_GT(colors(testing::render_scene(*gouraud, "raster")), 500u);
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
  const auto gouraud = raster_scene(body, {"raster.shading=\"gouraud\""});
  const auto phong = raster_scene(body, {"raster.shading=\"phong\""});
  const auto brightest = [](const Film& film) {
    double best = 0;
    for (const Color& c : film.pixels()) best = std::max(best, c.r);
    return best;
  };
  // At a corner: N·L = 1/√3 and R·V = 2/√54 ≈ 0.27, so I ≈ 0.2/√3 + 0.27^50 ≈ 0.115.
  const double gouraud_peak = brightest(testing::render_scene(*gouraud, "raster"));
  const double phong_peak = brightest(testing::render_scene(*phong, "raster"));
  EXPECT_NEAR(gouraud_peak, 0.2 / std::sqrt(3.0), 0.01);  // nothing brighter than the corners
  EXPECT_GT(phong_peak, 1.0);                             // kd + ks at the centre: 1.2
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
  const auto scene = raster_scene(body);
  const Film traced = testing::render_scene(*scene, "local");
  for (const char* shading : {"flat", "gouraud", "phong", "dotproduct"}) {
    const auto raster_view = raster_scene(body, {std::string("raster.shading=\"") + shading + "\""});
    const Film raster = testing::render_scene(*raster_view, "raster");
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
    // The default scene's adaptive anti-aliasing and Gaussian: its lattice not jittered (the
    // rasterizer draws the whole corner lattice), jittered as the scene has it (passes), and the
    // jittered mode.
    for (const char* sampling : {"aa.jitter=false", "aa.jitter=true", "aa.mode=\"jittered\""}) {
      const auto scene = load_default_scene({"camera.width=64", "camera.height=48", sampling,
                                             std::string("raster.shading=\"") + shading + "\""});
      const Film one = testing::render_scene(*scene, "raster", 1);
      const Film two = testing::render_scene(*scene, "raster", 2);
      ASSERT_EQ(one.pixels().size(), two.pixels().size());
      for (std::size_t i = 0; i < one.pixels().size(); ++i)
        ASSERT_TRUE(one.pixels()[i] == two.pixels()[i]) << shading << " " << sampling << " " << i;
    }
  }
}

// The jittered modes in passes of the accumulation buffer (camera/accumulation_buffer.h).
// An image of edges: a checkered floor and two boxes against the sky, all planar (the raster's
// triangles are the ray tracer's surfaces), lit by a directional light without shadows.
const char* kEdgesScene = R"(
  "camera": {"eye": [0.4, 1.6, 4], "target": [0, 0.3, 0], "fov": 45, "width": 48, "height": 36},
  "background": [0.2, 0.3, 0.8], "ambient": 0.15,
  "lights": [{"type": "directional", "direction": [-0.4, -1, -0.6], "intensity": 0.9}],
  "materials": {
    "floor": {"kd": {"type": "checker2d", "even": [0.9, 0.9, 0.85], "odd": [0.05, 0.05, 0.1], "mapping": {"type": "uv", "scale": 6}}},
    "red": {"kd": [0.8, 0.15, 0.1]}, "white": {"kd": 0.9}},
  "shapes": [
    {"type": "quad", "corner": [-3, 0, 3], "edge_u": [6, 0, 0], "edge_v": [0, 0, -6], "material": "floor"},
    {"type": "box", "min": [-1.1, 0, -0.6], "max": [-0.3, 0.9, 0.2], "material": "red"},
    {"type": "box", "min": [0.3, 0, -1.2], "max": [0.9, 1.4, -0.6], "material": "white"}],
  "local": {"shadows": false})";

// The root-mean-square difference of two images over every channel of every pixel.
double rms_difference(const Film& a, const Film& b) {
  double total = 0;
  for (std::size_t i = 0; i < a.pixels().size(); ++i)
    for (int c = 0; c < 3; ++c) total += std::pow(a.pixels()[i][c] - b.pixels()[i][c], 2);
  return std::sqrt(total / (3.0 * a.pixels().size()));
}

// The raster and the ray-traced local model share their shading: with the same jittered settings
// each estimates the same filtered image, and they lie as close to a 16 × 16 reference, and to
// each other, as two estimates of it may (the raster's pass offsets serve every pixel, the ray
// tracer's points are drawn per pixel: the same error, not the same bytes).
TEST(RasterRender, JitteredPassesMatchTheRayTracedLocalModel) {
  for (const char* filter : {"box", "gaussian"}) {
    const std::string with_filter = std::string("aa.filter=\"") + filter + "\"";
    const auto reference = raster_scene(kEdgesScene, {"aa.mode=\"uniform\"", "aa.n=16", with_filter});
    const Film exact = testing::render_scene(*reference, "local");
    const auto scene = raster_scene(kEdgesScene, {"aa.mode=\"jittered\"", "aa.n=4", with_filter});
    const Film raster = testing::render_scene(*scene, "raster");
    const Film traced = testing::render_scene(*scene, "local");
    const double raster_error = rms_difference(raster, exact), traced_error = rms_difference(traced, exact);
    std::printf("  %s: RMS against 16 × 16: raster %.4f, local %.4f; between them %.4f\n", filter,
                raster_error, traced_error, rms_difference(raster, traced));
    EXPECT_LT(raster_error, 0.02) << filter;
    EXPECT_LT(raster_error, 2 * traced_error) << filter;
    EXPECT_LT(rms_difference(raster, traced), 0.03) << filter;
  }
}

// Jittered passes, and adaptive with jitter, bring the raster's edges near a 16 × 16 reference of
// its own: far nearer than one sample a pixel; adaptive (4 passes, 64 where the contrast test
// asks) nearer than 16 jittered passes, with under half the samples of 8 × 8 everywhere.
TEST(RasterRender, JitteredPassesAntiAliasTheEdges) {
  const Film exact =
      testing::render_scene(*raster_scene(kEdgesScene, {"aa.mode=\"uniform\"", "aa.n=16"}), "raster");
  const double aliased = rms_difference(testing::render_scene(*raster_scene(kEdgesScene), "raster"), exact);
  const double jittered = rms_difference(
      testing::render_scene(*raster_scene(kEdgesScene, {"aa.mode=\"jittered\"", "aa.n=4"}), "raster"), exact);
  RunStatistics statistics;
  const Film adaptive_film = testing::render_scene(
      *raster_scene(kEdgesScene, {"aa.mode=\"adaptive\"", "aa.max_level=3", "aa.jitter=true"}), "raster", 2,
      statistics);
  const double adaptive = rms_difference(adaptive_film, exact);
  const nlohmann::json& passes = statistics.extra["raster"]["accumulation"];
  std::printf("  RMS against 16 × 16: one sample %.4f, jittered 4 × 4 %.4f, adaptive L = 3 %.4f (%s)\n",
              aliased, jittered, adaptive, passes.dump().c_str());
  EXPECT_LT(jittered, 0.35 * aliased);
  EXPECT_LT(adaptive, jittered);
  const auto pixels = uint64_t(48 * 36);
  EXPECT_EQ(passes["passes"].get<int>(), 64);
  EXPECT_GT(passes["refined_pixels"].get<uint64_t>(), pixels / 10);
  EXPECT_LT(passes["refined_pixels"].get<uint64_t>(), pixels / 2);
  EXPECT_LT(passes["samples"].get<uint64_t>(), 32 * pixels);
}

// A region of the image (--crop, a distributed tile) has the whole image's pixels, bit for bit,
// under a filter wider than a pixel: each pass's offset is the image's, and the region samples
// the ring of pixels its filter reaches.
TEST(RasterRender, JitteredPassesGiveARegionTheWholeImagesPixels) {
  for (const char* sampling : {"aa.jitter=true", "aa.mode=\"jittered\""}) {
    const auto scene = load_default_scene({"camera.width=40", "camera.height=30", sampling});
    const Film whole = testing::render_scene(*scene, "raster");
    const auto method = create_method(*find_method("raster"), *scene);
    RenderRequest request;
    request.region = {13, 7, 29, 22};
    request.quiet = true;
    const Film part = method->render(*scene, request).film;
    for (int y = 0; y < part.height(); ++y)
      for (int x = 0; x < part.width(); ++x)
        ASSERT_TRUE(part.at(x, y) == whole.at(x + 13, y + 7)) << sampling << " " << x << "," << y;
  }
}

// The scenes the raster once refused (Figures 49 and 50: adaptive with jitter).
TEST(RasterRender, TheSeedsJitteredScenesRender) {
  for (const char* name : {"two-mirrors.json", "two-mirrors-marble.json", "glass-globe.json"}) {
    const auto scene = load_scene_file(std::string(CANDELA_SOURCE_DIR) + "/scenes/" + name,
                                       {"camera.width=24", "camera.height=18"});
    ASSERT_TRUE(scene->antialiasing.jitter) << name;
    RunStatistics statistics;
    const Film film = testing::render_scene(*scene, "raster", 2, statistics);
    double brightest = 0;
    for (const Color& c : film.pixels()) brightest = std::max({brightest, c.r, c.g, c.b});
    EXPECT_GT(brightest, 0.1) << name;
    EXPECT_GE(statistics.extra["raster"]["accumulation"]["passes"].get<int>(), 4) << name;
  }
}

// The mean per-pixel difference between two images over the pixels both cover (not the
// background), and how many pixels one covers and the other does not.
struct Comparison {
  double mean = 0;
  int covered = 0, coverage_differs = 0;
};
Comparison compare(const Film& a, const Film& b, const Color& background) {
  Comparison result;
  double total = 0;
  for (int y = 0; y < a.height(); ++y)
    for (int x = 0; x < a.width(); ++x) {
      const bool a_background = a.at(x, y) == background, b_background = b.at(x, y) == background;
      if (a_background != b_background) ++result.coverage_differs;
      if (a_background || b_background) continue;
      ++result.covered;
      total += difference(a.at(x, y), b.at(x, y));
    }
  result.mean = result.covered ? total / result.covered : 0;
  return result;
}

// Review findings on the raster method, each a test that failed before its fix.
TEST(RasterRender, ShadowsMatchTheRayTracerWithoutSelfShadowing) {
  // A coarse sphere over a floor, shadows on: the sphere's own triangles lie inside it, yet it
  // must not shadow itself, and its shadow on the floor must be where ray casting puts it.
  const std::string body = R"(
    "camera": {"eye": [0, 3, 6], "target": [0, 0.5, 0], "fov": 50, "width": 64, "height": 48},
    "background": [0, 0, 1], "ambient": 0.1,
    "lights": [{"type": "point", "position": [2, 6, 2]}],
    "shapes": [{"type": "sphere", "center": [0, 1, 0], "radius": 1, "material": {"kd": [0.8, 0.5, 0.3]}},
               {"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "material": {"kd": 0.7}}],
    "raster": {"segments": 24, "shadows": true})";
  const auto scene = raster_scene(body);
  const Comparison c = compare(testing::render_scene(*scene, "raster"),
                               testing::render_scene(*scene, "local"), Color(0, 0, 1));
  EXPECT_GT(c.covered, 2000);
  EXPECT_LT(c.mean, 0.02) << c.mean;  // self-shadowing made the lit half of the sphere ambient-only
}

// "dotproduct" shading cast every light's shadow from its centre, so an area light's
// shadow had a hard edge where the ray tracer's has a penumbra. Now its samples, jittered per
// point as the ray tracer's are, each test their own shadow ray.
TEST(RasterRender, DotProductShadowsOfAnAreaLightHavePenumbrae) {
  const std::string body = R"(
    "camera": {"eye": [0, 1.2, 5], "target": [0, 0, 0], "fov": 40, "width": 64, "height": 64},
    "background": [0, 0, 1], "ambient": 0,
    "lights": [{"type": "area", "corner": [-1, 4, -1], "edge_u": [2, 0, 0], "edge_v": [0, 0, 2], "exitance": 10, "samples": 8}],
    "shapes": [{"type": "quad", "corner": [-0.6, 1.5, -0.6], "edge_u": [1.2, 0, 0], "edge_v": [0, 0, 1.2], "material": {"kd": 0}},
               {"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "material": {"kd": 0.7}}],
    "raster": {"shading": "dotproduct", "shadows": true, "segments": 8})";
  const auto scene = raster_scene(body);
  const Film raster = testing::render_scene(*scene, "raster");
  const Film traced = testing::render_scene(*scene, "local");
  // The floor's row through the middle (under the occluder, which the camera does not see), from
  // the umbra out to the fully lit floor:
  // the umbra's edge at |x| ≈ 0.24, the penumbra out to ≈ 1.2 (similar triangles of the light and
  // the occluder's edge at heights 4 and 1.5).
  int penumbra = 0;
  double largest_step = 0, brightest = 0;
  for (int x = 0; x < raster.width(); ++x) brightest = std::max(brightest, raster.at(x, 32).r);
  for (int x = 0; x < raster.width(); ++x) {
    const double value = raster.at(x, 32).r;
    if (value > 0.15 * brightest && value < 0.85 * brightest) ++penumbra;
    if (x > 0) largest_step = std::max(largest_step, std::fabs(value - raster.at(x - 1, 32).r));
  }
  EXPECT_GE(penumbra, 12);                    // a hard shadow has none (no anti-aliasing here)
  EXPECT_LT(largest_step, 0.25 * brightest);  // no jump from umbra to light
  const Comparison c = compare(raster, traced, Color(0, 0, 1));
  EXPECT_LT(c.mean, 0.03 * brightest) << c.mean;  // and where the ray tracer puts it
}

TEST(RasterRender, TheTerminatorFollowsTheInterpolatedNormal) {
  // Lit from the side: the light-dark boundary of a coarse Phong sphere is where the
  // interpolated normal turns from the light, not a staircase along the facets.
  const std::string body = R"(
    "camera": {"eye": [0, 0, 5], "target": [0, 0, 0], "fov": 40, "width": 64, "height": 64},
    "background": [0, 0, 1],
    "lights": [{"type": "point", "position": [10, 2, 0]}],
    "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1.2, "material": {"kd": 0.7}}],
    "raster": {"segments": 24}, "local": {"shadows": false})";
  const auto scene = raster_scene(body);
  const Film raster = testing::render_scene(*scene, "raster"),
             traced = testing::render_scene(*scene, "local");
  int disagree = 0;
  for (int y = 0; y < raster.height(); ++y)
    for (int x = 0; x < raster.width(); ++x) {
      if (raster.at(x, y) == Color(0, 0, 1) || traced.at(x, y) == Color(0, 0, 1)) continue;
      if ((raster.at(x, y).r > 0) != (traced.at(x, y).r > 0)) ++disagree;
    }
  EXPECT_LT(disagree, 20) << disagree;
}

TEST(RasterRender, PlanesAreRefinedSoGouraudLightsTheFloor) {
  // A floor under a point light: a plane's few huge triangles would put Gouraud's vertices a
  // hundred scene sizes away and leave the floor unlit.
  const std::string body = R"(
    "camera": {"eye": [0, 2, 6], "target": [0, 0, 0], "fov": 60, "width": 48, "height": 36},
    "background": [0, 0, 1], "ambient": 0.05,
    "lights": [{"type": "point", "position": [0, 3, 0]}],
    "shapes": [{"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "material": {"kd": 0.8}}])";
  for (const char* shading : {"flat", "gouraud", "dotproduct"}) {
    const auto scene = raster_scene(body, {std::string("raster.shading=\"") + shading + "\""});
    const Comparison c = compare(testing::render_scene(*scene, "raster"),
                                 testing::render_scene(*scene, "local"), Color(0, 0, 1));
    EXPECT_GT(c.covered, 1000) << shading;
    // Flat shading keeps its steps (one value per triangle); the others follow the light.
    EXPECT_LT(c.mean, std::string(shading) == "flat" ? 0.1 : 0.03) << shading << " " << c.mean;
  }
  // A scene of planes only, the eye near them: the floor is drawn, not left to the background.
  const auto only_plane =
      raster_scene(R"("camera": {"eye": [0, 0, 0], "target": [0, -0.5, -1], "width": 32, "height": 24},
      "background": [0, 0, 1], "ambient": 1, "shapes": [{"type": "plane", "point": [0, -1, 0], "normal": [0, 1, 0]}])");
  const Comparison c = compare(testing::render_scene(*only_plane, "raster"),
                               testing::render_scene(*only_plane, "local"), Color(0, 0, 1));
  EXPECT_EQ(c.coverage_differs, 0);
  EXPECT_GT(c.covered, 300);
}

TEST(RasterRender, MeshesKeepTheirOwnNormals) {
  // The cube mesh with flat normals (the mesh default) is faceted in both methods.
  const std::string source = CANDELA_SOURCE_DIR;
  const std::string body = R"(
    "camera": {"eye": [2.5, 2, 3], "target": [0.5, 0.5, 0.5], "width": 48, "height": 36},
    "background": [0, 0, 1], "ambient": 0.1, "lights": [{"type": "point", "position": [4, 5, 3]}],
    "shapes": [{"type": "mesh", "file": ")" +
                           source + R"(/scenes/meshes/cube.obj", "material": {"kd": 0.7}}],
    "local": {"shadows": false})";
  const auto scene = raster_scene(body);
  const Comparison c = compare(testing::render_scene(*scene, "raster"),
                               testing::render_scene(*scene, "local"), Color(0, 0, 1));
  EXPECT_GT(c.covered, 200);
  EXPECT_LT(c.mean, 1e-6) << c.mean;
}

TEST(RasterRender, CameraInsideASphereAndOrthographicViews) {
  // Most triangles behind the eye: clipped, not smeared over every tile; the inside is drawn.
  const auto inside =
      raster_scene(R"("camera": {"eye": [0, 0, 0], "target": [0, 0, -1], "width": 32, "height": 24},
      "background": [0, 0, 1], "ambient": 1, "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 3}])");
  const Comparison c = compare(testing::render_scene(*inside, "raster"),
                               testing::render_scene(*inside, "local"), Color(0, 0, 1));
  EXPECT_EQ(c.coverage_differs, 0);
  EXPECT_EQ(c.covered, 32 * 24);
  const auto orthographic = raster_scene(
      R"("camera": {"type": "orthographic", "eye": [0, 0, 5], "target": [0, 0, 0], "window": [-2, 2, -1.5, 1.5], "width": 32, "height": 24},
      "background": [0, 0, 1], "ambient": 0.2, "lights": [{"type": "directional", "direction": [0, 0, -1]}],
      "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1}], "raster": {"segments": 128}, "local": {"shadows": false})");
  const Comparison o = compare(testing::render_scene(*orthographic, "raster"),
                               testing::render_scene(*orthographic, "local"), Color(0, 0, 1));
  EXPECT_GT(o.covered, 150);
  EXPECT_LT(o.coverage_differs, 12);
  EXPECT_LT(o.mean, 0.01);
}

TEST(RasterRender, SettingsAreChecked) {
  EXPECT_THROW(raster_scene(kSphereScene, {"raster.shading=\"toon\""}), InputError);
  EXPECT_THROW(raster_scene(kSphereScene, {"raster.segments=2"}), InputError);
  EXPECT_THROW(raster_scene(kSphereScene, {"raster.crease_angle=200"}), InputError);
  // Dot-product shading carries four values per light: too many lights is a clear error.
  std::string lights = R"("lights": [)";
  for (int i = 0; i < 20; ++i)
    lights += std::string(i ? ", " : "") + R"({"type": "point", "position": [0, 5, 5]})";
  const auto crowded =
      raster_scene(R"("camera": {"width": 8, "height": 8}, )" + lights +
                   R"(], "shapes": [{"type": "sphere"}], "raster": {"shading": "dotproduct"})");
  try {
    testing::render_scene(*crowded, "raster");
    FAIL() << "expected an error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("at most"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace candela
