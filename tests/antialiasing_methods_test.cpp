// SPEC §17: every image-producing method takes its pixels from the one camera sampling and
// reconstruction (camera/antialiasing.h) — every aa mode and pixel filter honoured, with the same
// bytes on one and two threads (the rasterizing views too, the jittered modes in passes,
// camera/accumulation_buffer.h); a rasterizing view's grid too large to hold is refused before any
// work with an error naming the method and the setting.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "integrators/method_registry.h"
#include "integrators/scene_loading.h"
#include "util/error.h"

namespace candela {
namespace {

// A method as its entry makes it, with settings of its own object.
struct MethodVariant {
  std::string method;
  std::vector<std::string> settings;
  std::string label() const { return method + (settings.empty() ? "" : " " + settings[0]); }
};

std::vector<MethodVariant> every_method_view() {
  std::vector<MethodVariant> all{{"local", {}},
                                 {"whitted", {}},
                                 {"raster", {"shading=\"phong\""}},
                                 {"raster", {"shading=\"gouraud\""}},
                                 {"radiosity", {"display=\"gouraud\""}},
                                 {"path", {"spp=1"}}};
  for (const char* display : {"flat", "ray-traced", "elements"})
    all.push_back({"radiosity", {std::string("display=\"") + display + "\""}});
  for (const char* display : {"global", "direct", "indirect", "hybrid"})
    all.push_back({"meshless", {std::string("display=\"") + display + "\""}});
  return all;
}

// A small room every method lights: a point light for the local model, an emissive quad for
// radiosity, ambient light, and edges (a box, a sphere, the walls) for the filters to act on.
const char* const kRoom = R"({
  "format": "candela/1",
  "camera": {"eye": [0, 1.2, 4], "target": [0, 0.8, 0], "fov": 60, "width": 18, "height": 14},
  "background": [0.2, 0.3, 0.5],
  "ambient": 0.2,
  "lights": [{"type": "point", "position": [1, 2.5, 2], "intensity": 1}],
  "radiosity": {"patch_size": 1, "element_size": 1, "hemicube_resolution": 20},
  "meshless": {"spacing": 0.6, "grid": 8, "rounds": 1},
  "path": {"spp": 1},
  "materials": {"white": {"kd": 0.7}, "red": {"kd": [0.7, 0.2, 0.1]}, "lamp": {"kd": 0, "emission": 8}},
  "shapes": [
    {"type": "quad", "corner": [-2, 0, 2], "edge_u": [4, 0, 0], "edge_v": [0, 0, -4], "material": "white"},
    {"type": "quad", "corner": [-2, 0, -2], "edge_u": [4, 0, 0], "edge_v": [0, 3, 0], "material": "white"},
    {"type": "box", "min": [-0.5, 0, -0.5], "max": [0.3, 0.9, 0.3], "material": "red"},
    {"type": "sphere", "center": [0.9, 0.5, 0.4], "radius": 0.5, "material": "white"},
    {"type": "quad", "corner": [-0.5, 2.9, -0.5], "edge_u": [1, 0, 0], "edge_v": [0, 0, 1], "material": "lamp"}
  ]
})";

std::unique_ptr<Scene> room() {
  return load_scene_text(kRoom, "room.json", ".");
}

std::vector<AntialiasingSettings> every_mode() {
  std::vector<AntialiasingSettings> all;
  for (const AntialiasingMode mode :
       {AntialiasingMode::none, AntialiasingMode::uniform, AntialiasingMode::jittered,
        AntialiasingMode::corners, AntialiasingMode::adaptive}) {
    AntialiasingSettings settings;
    settings.mode = mode;
    settings.n = 2;
    settings.max_level = 2;
    settings.threshold = Color(0.05);  // subdivide on every visible edge
    all.push_back(settings);
    if (mode == AntialiasingMode::corners || mode == AntialiasingMode::adaptive) {
      settings.jitter = true;
      all.push_back(settings);
    }
  }
  return all;
}

Film render_with(const Method& method, const Scene& scene, std::size_t threads) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  RenderRequest request;
  request.region = {0, 0, scene.camera->width(), scene.camera->height()};
  request.quiet = true;
  return method.render(scene, request).film;
}

TEST(EveryMethodSampling, OneAndTwoThreadsGiveTheSameBytesForEveryFilterAndMode) {
  auto scene = room();
  for (const MethodVariant& variant : every_method_view()) {
    scene->antialiasing = {};
    const auto method = create_method(*find_method(variant.method), *scene, variant.settings);
    int rendered = 0;
    for (const PixelFilterEntry& filter : pixel_filter_entries()) {
      for (AntialiasingSettings settings : every_mode()) {
        settings.filter = filter.name;
        scene->antialiasing = settings;
        const std::string what = variant.label() + ", aa.mode " +
                                 std::string(kAntialiasingModeNames.name(settings.mode)) +
                                 (settings.jitter ? " with jitter" : "") + ", filter " + filter.name;
        EXPECT_NO_THROW(create_method(*find_method(variant.method), *scene, variant.settings)) << what;
        EXPECT_NO_THROW(refuse_unsupported_antialiasing(*method, *scene)) << what;
        const Film one = render_with(*method, *scene, 1);
        const Film two = render_with(*method, *scene, 2);
        ASSERT_EQ(one.pixels().size(), two.pixels().size());
        double brightest = 0;
        for (const Color& c : one.pixels()) brightest = std::max({brightest, c.r, c.g, c.b});
        EXPECT_GT(brightest, 0.1) << what;  // an image, not a black film
        EXPECT_EQ(std::memcmp(one.pixels().data(), two.pixels().data(), one.pixels().size() * sizeof(Color)),
                  0)
            << what;
        ++rendered;
      }
    }
    EXPECT_GT(rendered, 0) << variant.label();
  }
}

bool same_bytes(const Film& a, const Film& b) {
  return a.pixels().size() == b.pixels().size() &&
         std::memcmp(a.pixels().data(), b.pixels().data(), a.pixels().size() * sizeof(Color)) == 0;
}

// A render's own seed and aa settings go down in the RenderRequest (candela.render(seed=,
// spp=) in Python) rather than into the Scene: every method gives the image of the scene loaded
// with them, byte for byte, and a method that keeps its solution between renders (radiosity,
// meshless) does not reuse the one it made with the scene's seed.
TEST(EveryMethodSampling, ARequestsSeedAndAntialiasingGiveTheImageOfTheSceneLoadedWithThem) {
  const auto scene = room();
  const uint64_t seed = 77;
  const std::string room_text = kRoom;
  const std::string format = "\"format\": \"candela/1\",";
  for (const MethodVariant& variant : every_method_view()) {
    AntialiasingSettings antialiasing;
    antialiasing.mode = AntialiasingMode::jittered;
    antialiasing.n = 2;
    std::string text = room_text;
    text.insert(text.find(format) + format.size(),
                fmt::format(R"( "render": {{"seed": {}}}, "aa": {{"mode": "jittered", "n": 2}},)", seed));
    const auto loaded = load_scene_text(text, "room.json", ".");
    ASSERT_EQ(loaded->render.seed, seed);
    const auto method = create_method(*find_method(variant.method), *scene, variant.settings, antialiasing);
    RenderRequest request;
    request.region = {0, 0, scene->camera->width(), scene->camera->height()};
    request.quiet = true;
    // The scene's own first, so that a kept solution would be the scene seed's.
    const RenderResult plain = method->render(*scene, request);
    request.seed = seed;
    request.antialiasing = antialiasing;
    const RenderResult overridden = method->render(*scene, request);
    const Film expected =
        render_with(*create_method(*find_method(variant.method), *loaded, variant.settings), *loaded, 2);
    EXPECT_TRUE(same_bytes(overridden.film, expected)) << variant.label();
    EXPECT_FALSE(same_bytes(overridden.film, plain.film)) << variant.label();
    if (variant.method == "radiosity") {
      EXPECT_FALSE(overridden.statistics.extra["radiosity"]["solution_reused"].get<bool>());
    }
    if (variant.method == "meshless") {
      EXPECT_FALSE(overridden.statistics.extra["meshless"]["geometry_reused"].get<bool>());
    }
    // The scene is as it was: its own render again gives the first image.
    request.seed.reset();
    request.antialiasing.reset();
    EXPECT_TRUE(same_bytes(method->render(*scene, request).film, plain.film)) << variant.label();
    EXPECT_EQ(scene->render.seed, 0u);
    EXPECT_EQ(scene->antialiasing.mode, AntialiasingSettings{}.mode);
  }
}

// The seed alone (the aa settings the scene's): the path tracer and the ray tracers, whose images
// it changes, give the image of the scene loaded with it.
TEST(EveryMethodSampling, ARequestsSeedAloneGivesTheImageOfTheSceneLoadedWithIt) {
  const auto scene = room();
  std::string text = kRoom;
  const std::string format = "\"format\": \"candela/1\",";
  text.insert(text.find(format) + format.size(), R"( "render": {"seed": 12345},)");
  const auto loaded = load_scene_text(text, "room.json", ".");
  for (const char* name : {"path", "whitted", "local"}) {
    const auto method = create_method(*find_method(name), *scene);
    RenderRequest request;
    request.region = {0, 0, scene->camera->width(), scene->camera->height()};
    request.quiet = true;
    request.seed = 12345;
    const Film overridden = method->render(*scene, request).film;
    const Film expected = render_with(*create_method(*find_method(name), *loaded), *loaded, 2);
    EXPECT_TRUE(same_bytes(overridden, expected)) << name;
    request.seed.reset();
    EXPECT_FALSE(same_bytes(method->render(*scene, request).film, expected)) << name;
  }
}

// The filter reaches every method's pixels: a wider Gaussian changes each method's image (the
// rasterized views and the ray-cast displays alike), and aa.mode "uniform" changes it again.
TEST(EveryMethodSampling, TheFilterAndTheModeReachEveryMethodThatTakesThem) {
  auto scene = room();
  for (const MethodVariant& variant : every_method_view()) {
    scene->antialiasing = {};
    const auto method = create_method(*find_method(variant.method), *scene, variant.settings);
    const Film plain = render_with(*method, *scene, 2);
    scene->antialiasing.filter = "gaussian";
    const Film filtered = render_with(*method, *scene, 2);
    EXPECT_NE(
        std::memcmp(plain.pixels().data(), filtered.pixels().data(), plain.pixels().size() * sizeof(Color)),
        0)
        << variant.label();
    scene->antialiasing.filter = "box";
    scene->antialiasing.mode = AntialiasingMode::uniform;
    scene->antialiasing.n = 3;
    const Film supersampled = render_with(*method, *scene, 2);
    EXPECT_NE(
        std::memcmp(plain.pixels().data(), filtered.pixels().data(), plain.pixels().size() * sizeof(Color)),
        0)
        << variant.label();
    EXPECT_NE(std::memcmp(plain.pixels().data(), supersampled.pixels().data(),
                          plain.pixels().size() * sizeof(Color)),
              0)
        << variant.label();
  }
}

// A rasterized view's grid is checked for every view the scene can be rendered from (its named
// cameras, candela render --camera), before any work: a small main camera does not let a huge
// named view through to allocate its grid.
TEST(EveryMethodSampling, TheGridOfEveryNamedViewIsCheckedBeforeAnyWork) {
  std::string text = kRoom;
  const std::string camera =
      R"("camera": {"eye": [0, 1.2, 4], "target": [0, 0.8, 0], "fov": 60, "width": 18, "height": 14},)";
  ASSERT_NE(text.find(camera), std::string::npos);
  text.replace(
      text.find(camera), camera.size(),
      camera +
          R"( "cameras": [{"name": "poster", "eye": [0, 1.2, 4], "target": [0, 0.8, 0], "width": 12000, "height": 9000}],)");
  const auto scene = load_scene_text(text, "room.json", ".", {"aa.mode=uniform", "aa.n=4"});
  for (const char* method : {"raster", "radiosity"}) {
    try {
      (void)create_method(*find_method(method), *scene,
                          {std::string(method) == "radiosity" ? "display=\"gouraud\"" : "shading=\"phong\""});
      ADD_FAILURE() << method << ": the 48000 × 36000 grid of \"poster\" was not refused";
    } catch (const InputError& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find(std::string(method) + " cannot do aa.n 4"), std::string::npos) << message;
      EXPECT_NE(message.find("for camera \"poster\""), std::string::npos) << message;
    }
  }
  // The ray-cast views take it (their samples are not held at once).
  EXPECT_NO_THROW((void)create_method(*find_method("local"), *scene));
}

}  // namespace
}  // namespace candela
