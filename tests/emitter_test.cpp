// One emitter model: three small closed-or-open diffuse rooms, each lit by one kind of
// emitter only — (a) a point light, (b) an emissive quad, (c) a constant sky seen through the open
// top — rendered by radiosity, meshless (hybrid and global displays) and the path tracer: every
// method's mean luminance within 3 % of the path tracer's (radiosity within 2 %), and the
// direct-only images (local, against path with one bounce) within 1 %. No method gives a black
// image for a lit scene.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "integrators/light_sampler.h"
#include "integrators/method_registry.h"
#include "integrators/scene_loading.h"
#include "math/constants.h"
#include "render_support.h"
#include "scene/environment_light.h"
#include "scene/surface_light.h"
#include "util/error.h"

namespace candela {
namespace {

// A 4 × 4 × 4 room of diffuse quads (floor 0.5, back 0.6, sides 0.4, front 0.5, ceiling 0.5 unless
// open), the camera inside; `emitters` adds the lights, materials or environment, `more_shapes`
// shapes. Radiosity's hemicube (50) and meshless's spacing (0.2 m, 1,236 sites) are coarser than
// the defaults, for CI's sanitizer run: measured, every ratio below stays within 1.3 % of 1
// (radiosity 1.2 % under the sky, meshless 1.3 % global under the lamp) in half the time the
// defaults take.
std::string room(const std::string& emitters, bool open_top, const std::string& more_shapes = "") {
  const auto quad = [](const char* corner, const char* u, const char* v, double kd) {
    return std::string(R"({"type": "quad", "corner": )") + corner + R"(, "edge_u": )" + u +
           R"(, "edge_v": )" + v + R"(, "material": {"kd": )" + std::to_string(kd) + "}}";
  };
  std::string shapes = quad("[0, 0, 0]", "[0, 0, 4]", "[4, 0, 0]", 0.5) + ", " +
                       quad("[0, 0, 0]", "[4, 0, 0]", "[0, 4, 0]", 0.6) + ", " +
                       quad("[0, 0, 0]", "[0, 4, 0]", "[0, 0, 4]", 0.4) + ", " +
                       quad("[4, 0, 0]", "[0, 0, 4]", "[0, 4, 0]", 0.4) + ", " +
                       quad("[0, 0, 4]", "[0, 4, 0]", "[4, 0, 0]", 0.5);
  if (!open_top) shapes += ", " + quad("[0, 4, 0]", "[4, 0, 0]", "[0, 0, 4]", 0.5);
  shapes += more_shapes;
  return R"({"format": "candela/1",
    "camera": {"eye": [2, 2, 3.9], "target": [2, 1.6, 0], "fov": 70, "width": 16, "height": 12},
    "radiosity": {"patch_size": 0.5, "element_size": 0.5, "threshold": 0.001, "hemicube_resolution": 50},
    "meshless": {"spacing": 0.2},
    "path": {"spp": 1024},
    "render": {"environment_light_samples": 16},
    "shapes": [)" +
         shapes + "]" + emitters + "}";
}

const char* kPointLight =
    R"(, "lights": [{"type": "point", "position": [2, 3.5, 2], "intensity": 4, "attenuation": "inverse-square"}])";
const char* kEmissiveQuad = R"(, "materials": {"lamp": {"kd": 0, "emission": 4}})";
const char* kSky = R"(, "environment": {"type": "constant", "color": [1, 1, 1]})";

double mean_luminance(const Film& film) {
  double sum = 0;
  for (const Color& pixel : film.pixels()) sum += luminance(pixel);
  return sum / double(film.pixels().size());
}

struct Case {
  const char* name;
  std::string scene;
};

std::vector<Case> cases() {
  // The lamp: a 1 × 1 quad facing down just below the ceiling (radiosity patches are one-sided:
  // the light its back sends up onto the ceiling stays between the two).
  const std::string lamp = room(
      kEmissiveQuad, false,
      R"(, {"type": "quad", "corner": [1.5, 3.999, 1.5], "edge_u": [1, 0, 0], "edge_v": [0, 0, 1], "material": "lamp"})");
  return {{"point light", room(kPointLight, false)},
          {"emissive quad", lamp},
          {"sky through the open top", room(kSky, true)}};
}

// One test a kind of emitter (ctest runs them side by side).
class EveryMethodSeesTheEmitter : public ::testing::TestWithParam<int> {};

TEST_P(EveryMethodSeesTheEmitter, WithinTheToleranceOfThePathTracer) {
  const Case c = cases()[static_cast<std::size_t>(GetParam())];
  const auto scene = load_scene_text(c.scene, "room.json", ".");
  const double reference = mean_luminance(testing::render_scene(*scene, "path"));
  ASSERT_GT(reference, 0.01) << c.name;
  const double radiosity = mean_luminance(testing::render_scene(*scene, "radiosity"));
  EXPECT_NEAR(radiosity / reference, 1, 0.02) << c.name << ": radiosity";
  for (const char* display : {"hybrid", "global"}) {
    const auto meshless_scene =
        load_scene_text(c.scene, "room.json", ".", {std::string("meshless.display=") + display});
    const double meshless = mean_luminance(testing::render_scene(*meshless_scene, "meshless"));
    EXPECT_NEAR(meshless / reference, 1, 0.03) << c.name << ": meshless " << display;
  }
  // Direct light alone: the local model against the path tracer with one bounce.
  const auto one_bounce = load_scene_text(c.scene, "room.json", ".", {"path.max_depth=1"});
  const double direct_reference = mean_luminance(testing::render_scene(*one_bounce, "path"));
  // 4 × 4 samples a pixel, box-filtered: the pixel's area, as the path tracer's random points.
  const auto supersampled = load_scene_text(c.scene, "room.json", ".", {"aa.mode=uniform", "aa.n=4"});
  const double local = mean_luminance(testing::render_scene(*supersampled, "local"));
  ASSERT_GT(direct_reference, 0.005) << c.name;
  EXPECT_NEAR(local / direct_reference, 1, 0.01) << c.name << ": local";
  EXPECT_GT(mean_luminance(testing::render_scene(*supersampled, "whitted")), 0.9 * local) << c.name;
}

INSTANTIATE_TEST_SUITE_P(Emitters, EveryMethodSeesTheEmitter, ::testing::Values(0, 1, 2),
                         [](const ::testing::TestParamInfo<int>& info) {
                           return std::string(info.param == 0   ? "PointLight"
                                              : info.param == 1 ? "EmissiveQuad"
                                                                : "SkyThroughTheOpenTop");
                         });

// The emissive surfaces and the environment are lights of the scene: made by the
// loader, one per emissive object, with the samples the scene asks for.
TEST(Emitters, EmissiveObjectsAndTheEnvironmentBecomeLights) {
  const auto scene = load_scene_text(room(kSky, true), "room.json", ".", {"render.surface_light_samples=3"});
  EXPECT_TRUE(scene->surface_lights.empty());
  ASSERT_TRUE(scene->environment_light);
  EXPECT_EQ(scene->environment_light->sample_count(), 16 * 16);
  EXPECT_EQ(scene->emitter_count(), 1u);
  const auto lit = load_scene_text(cases()[1].scene, "room.json", ".", {"render.surface_light_samples=3"});
  ASSERT_EQ(lit->surface_lights.size(), 1u);
  EXPECT_EQ(lit->surface_lights[0]->sample_count(), 9);
  EXPECT_EQ(lit->surface_lights[0]->type_name(), "surface");
  EXPECT_DOUBLE_EQ(lit->surface_lights[0]->area(), 1.0);
  EXPECT_FALSE(lit->environment_light);
}

// The path tracer's light selection reads the one emitter model: each emitter by its power
// (Light::power, the scene's bounding radius for the point light and the sky), and a BSDF ray
// that hits a lamp is weighed with the very density next-event estimation draws it with.
TEST(Emitters, ThePathTracerChoosesEmittersByPowerAndWeighsHitsByTheirDensity) {
  const std::string lamp =
      R"(, {"type": "quad", "corner": [1.5, 3.5, 1.5], "edge_u": [1, 0, 0], "edge_v": [0, 0, 1], "material": "lamp"})";
  const std::string emitters = std::string(R"(, "materials": {"lamp": {"kd": 0, "emission": 4}})") +
                               R"(, "environment": {"type": "constant", "color": [1, 1, 1]})" +
                               R"(, "lights": [{"type": "point", "position": [2, 3, 2], "intensity": 4}])";
  const auto scene = load_scene_text(room(emitters, true, lamp), "room.json", ".");
  ASSERT_EQ(scene->emitter_count(), 3u);  // the point light, the lamp, the sky
  const LightSampler lights(*scene);
  const double r = 0.5 * length(scene->bounds().diagonal());  // the room: r² = 12
  EXPECT_NEAR(r * r, 12, 1e-9);
  // Point light without attenuation: 4 · 4π r²; the lamp: 4 · 2 sides · 1 m²; the sky: 1 · 4π r².
  const double powers[] = {4 * 4 * kPi * 12, 8, 4 * kPi * 12};
  const double total = powers[0] + powers[1] + powers[2];
  for (std::size_t i = 0; i < 3; ++i) EXPECT_NEAR(lights.probability(i), powers[i] / total, 1e-12) << i;
  int picked[3] = {0, 0, 0};
  for (int k = 0; k < 1000; ++k) ++picked[lights.choose((k + 0.5) / 1000).emitter];
  EXPECT_NEAR(picked[1], 1000 * powers[1] / total, 1);
  // The lamp's sample from a floor point, and the ray toward it: the same density both ways.
  const Vec3 floor_point{2.2, 0, 1.7};
  LightSample sample;
  ASSERT_TRUE(scene->emitter(1).illuminate_random(floor_point, {0.3, 0.8}, sample));
  Intersection hit;
  ASSERT_TRUE(scene->intersect(Ray{floor_point + Vec3{0, 1e-6, 0}, sample.direction}, hit));
  EXPECT_NEAR(length(hit.surface.position - floor_point), sample.distance, 1e-5);
  EXPECT_NEAR(
      lights.surface_pdf(hit.primitive, floor_point, hit.surface) / (lights.probability(1) * sample.pdf), 1,
      1e-4);
  EXPECT_EQ(scene->emitter(1).emitted_radiance(sample.direction), scene->material_of(hit).emission);
  EXPECT_NEAR(lights.environment_pdf({0, 1, 0}), lights.probability(2) / (4 * kPi), 1e-12);
  EXPECT_EQ(lights.emissive_primitive_count(), 1u);
}

}  // namespace
}  // namespace candela

namespace candela {
namespace {

// Bad input: an emitter a method cannot account for is an error naming both and where
// the emitter is, never a dark image. An emissive unbounded plane cannot be sampled for shadow
// rays; the path tracer and radiosity (which meshes it within the scene's bounds) take it.
TEST(Emitters, AnEmitterAMethodCannotSampleIsRefusedNamingBoth) {
  const auto scene = load_scene_text(R"({"format": "candela/1",
    "camera": {"eye": [0, 2, 4], "target": [0, 0, 0], "width": 4, "height": 4},
    "shapes": [
      {"type": "sphere", "center": [0, 0.5, 0], "radius": 0.5, "material": {"kd": 0.5}},
      {"name": "glowing floor", "type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "material": {"kd": 0, "emission": 1}}]})",
                                     "glow.json", ".");
  ASSERT_EQ(scene->unsampled_emitters.size(), 1u);
  for (const char* method : {"local", "whitted", "raster", "meshless"}) {
    try {
      (void)create_method(*find_method(method), *scene);
      ADD_FAILURE() << method << " accepted an emitter it cannot sample";
    } catch (const InputError& e) {
      EXPECT_EQ(e.location().file, "glow.json") << method;
      EXPECT_EQ(e.location().line, 5) << method;  // the plane's entry
      EXPECT_NE(e.message().find(std::string(method) +
                                 " cannot light the scene by the emissive plane \"glowing floor\""),
                std::string::npos)
          << e.message();
      EXPECT_NE(e.message().find("radiosity or path"), std::string::npos) << e.message();
    }
  }
  EXPECT_NO_THROW((void)create_method(*find_method("path"), *scene));
  EXPECT_NO_THROW((void)create_method(*find_method("radiosity"), *scene));
}

// The refusal comes from create_method, before any work (the tessellation, the item buffers).
TEST(Emitters, DotProductShadingRefusesTheEnvironment) {
  const auto scene = load_scene_text(room(kSky, true), "room.json", ".", {"raster.shading=dotproduct"});
  try {
    (void)create_method(*find_method("raster"), *scene);
    ADD_FAILURE() << "dotproduct shading accepted an environment light";
  } catch (const InputError& e) {
    EXPECT_EQ(e.location().json_path, "raster.shading");
    EXPECT_NE(e.message().find("raster cannot light the scene by the environment"), std::string::npos)
        << e.message();
  }
}

// --stats and candela report say which emitters a method accounted for, and how.
TEST(Emitters, FactsListTheScenesEmittersAndHowTheMethodTakesThem) {
  const auto scene = load_scene_text(cases()[1].scene, "room.json", ".");
  const nlohmann::json facts = emitter_facts(*scene, *find_method("radiosity"));
  EXPECT_TRUE(facts["lights"].empty());
  ASSERT_EQ(facts["emissive_surfaces"].size(), 1u);
  EXPECT_EQ(facts["emissive_surfaces"][0], "quad#6");
  EXPECT_TRUE(facts["environment"].is_null());
  EXPECT_FALSE(facts["background_lights"].get<bool>());
  EXPECT_NE(facts["accounted_by"].get<std::string>().find("first shot"), std::string::npos);
  const nlohmann::json point =
      emitter_facts(*load_scene_text(cases()[0].scene, "room.json", "."), *find_method("path"));
  EXPECT_EQ(point["lights"]["point"], 1);
}

}  // namespace
}  // namespace candela
