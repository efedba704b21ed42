// Issue 7 end to end: classic radiosity (000 §6, SPEC §10) — emissive materials and the
// radiosity mesh inside whole scenes.
#include <gtest/gtest.h>

#include "render_support.h"

#include <tbb/global_control.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "integrators/method_registry.h"
#include "integrators/radiosity_method.h"
#include "integrators/whitted.h"
#include "scene/scene_loader.h"

namespace candela {
namespace {

std::unique_ptr<Scene> scene_from(const std::string& body, const std::string& camera) {
  return load_scene_text(R"({"format": "candela/1", "camera": )" + camera + ", " + body + "}", "test.json", ".");
}

// One pixel looking down −z through the image centre.
const char* kCentreCamera = R"({"eye": [0, 0, 10], "target": [0, 0, 0], "fov": 1, "width": 1, "height": 1})";

Color centre_pixel(const Scene& scene) {
  Color radiance;
  WhittedMethod().pixel_ray_tree(scene, 0, 0, radiance);
  return radiance;
}

TEST(RadiosityEmission, MaterialReadsEmissionDefaultingToBlack) {
  const auto emissive = scene_from(
      R"("shapes": [{"type": "plane", "point": [0, 0, 0], "normal": [0, 0, 1], "material": {"kd": 0.5, "emission": [1, 0.5, 0.25]}}])",
      kCentreCamera);
  const Color e = emissive->materials.back().emission;
  EXPECT_EQ(e.r, 1);
  EXPECT_EQ(e.g, 0.5);
  EXPECT_EQ(e.b, 0.25);
  const auto plain = scene_from(
      R"("shapes": [{"type": "plane", "point": [0, 0, 0], "normal": [0, 0, 1], "material": {"kd": 0.5}}])", kCentreCamera);
  EXPECT_TRUE(plain->materials.back().emission.is_black());
}

TEST(RadiosityEmission, NegativeEmissionIsRefused) {
  EXPECT_THROW(scene_from(R"("shapes": [{"type": "plane", "point": [0, 0, 0], "normal": [0, 0, 1], "material": {"emission": [1, -0.5, 0]}}])",
                          kCentreCamera),
               std::exception);
}

TEST(RadiosityEmission, RayTracerShowsSelfLuminousSurfacesWithoutLights) {
  // A black, unlit plane that emits: the local model shows exactly its emission (ka = kd = 0,
  // so the ambient term adds nothing, and no light reaches it).
  const auto scene = scene_from(
      R"("ambient": [0.3, 0.3, 0.3], "shapes": [{"type": "plane", "point": [0, 0, 0], "normal": [0, 0, 1], "material": {"kd": 0, "emission": [0.7, 0.2, 0.1]}}])",
      kCentreCamera);
  const Color got = centre_pixel(*scene);
  EXPECT_NEAR(got.r, 0.7, 1e-12);
  EXPECT_NEAR(got.g, 0.2, 1e-12);
  EXPECT_NEAR(got.b, 0.1, 1e-12);
  // Lit and emitting: emission adds to what the lights give.
  const auto lit = scene_from(
      R"("lights": [{"type": "point", "position": [0, 0, 5]}], "shapes": [{"type": "plane", "point": [0, 0, 0], "normal": [0, 0, 1], "material": {"kd": 0.5}}])",
      kCentreCamera);
  const auto lit_emitting = scene_from(
      R"("lights": [{"type": "point", "position": [0, 0, 5]}], "shapes": [{"type": "plane", "point": [0, 0, 0], "normal": [0, 0, 1], "material": {"kd": 0.5, "emission": 0.25}}])",
      kCentreCamera);
  const Color base = centre_pixel(*lit), glowing = centre_pixel(*lit_emitting);
  EXPECT_NEAR(glowing.r - base.r, 0.25, 1e-12);
  EXPECT_NEAR(glowing.g - base.g, 0.25, 1e-12);
  EXPECT_NEAR(glowing.b - base.b, 0.25, 1e-12);
}

// A closed cube [0, 2]³ of six quads facing inward, every one emitting E and reflecting ρ.
std::string furnace_scene(const std::string& radiosity) {
  const std::string material = R"("material": {"kd": 0.6, "emission": 1})";
  return R"("radiosity": )" + radiosity + R"(, "shapes": [
      {"type": "quad", "corner": [0, 0, 0], "edge_u": [0, 0, 2], "edge_v": [2, 0, 0], )" + material + R"(},
      {"type": "quad", "corner": [0, 2, 0], "edge_u": [2, 0, 0], "edge_v": [0, 0, 2], )" + material + R"(},
      {"type": "quad", "corner": [0, 0, 0], "edge_u": [0, 2, 0], "edge_v": [0, 0, 2], )" + material + R"(},
      {"type": "quad", "corner": [2, 0, 0], "edge_u": [0, 0, 2], "edge_v": [0, 2, 0], )" + material + R"(},
      {"type": "quad", "corner": [0, 0, 0], "edge_u": [2, 0, 0], "edge_v": [0, 2, 0], )" + material + R"(},
      {"type": "quad", "corner": [0, 0, 2], "edge_u": [0, 2, 0], "edge_v": [2, 0, 0], )" + material + R"(}])";
}

const char* kFurnaceCamera = R"({"eye": [1, 1, 1.9], "target": [1, 1, 0], "fov": 80, "width": 16, "height": 16})";

// The furnace (000 eq. 6-7 in a closed enclosure of uniform E and ρ): B = E + ρB, so every
// element's B = E / (1 − ρ) = 2.5, whatever the form factors, as long as every row sums to 1.
void expect_furnace(const std::string& radiosity) {
  const auto scene = scene_from(furnace_scene(radiosity), kFurnaceCamera);
  const RadiositySolveResult result = solve_radiosity(*scene, true);
  ASSERT_FALSE(result.mesh.elements.empty());
  EXPECT_GT(result.mesh.elements.size(), result.mesh.patches.size());
  for (const Color& b : result.element_radiosity) {
    EXPECT_NEAR(b.r, 2.5, 0.025);
    EXPECT_NEAR(b.g, 2.5, 0.025);
    EXPECT_NEAR(b.b, 2.5, 0.025);
  }
  // Through the whole method: every pixel shows the furnace's radiosity.
  const auto method = find_method("radiosity")->create();
  Film film(16, 16);
  RunStatistics statistics;
  method->render(*scene, {{0, 0, 16, 16}, true}, film, statistics);
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) EXPECT_NEAR(film.at(x, y).g, 2.5, 0.025);
  const auto& facts = statistics.extra["radiosity"];
  EXPECT_EQ(facts["patches"], result.mesh.patches.size());
  EXPECT_EQ(facts["elements"], result.mesh.elements.size());
  // Closed: every form-factor row sums to about 1 (000 eq. 6-6).
  EXPECT_NEAR(facts["row_sum"]["min"].get<double>(), 1, 0.01);
  EXPECT_NEAR(facts["row_sum"]["max"].get<double>(), 1, 0.01);
  if (facts.contains("reciprocity_error")) {
    EXPECT_LT(facts["reciprocity_error"].get<double>(), 0.5);
  }
}

TEST(RadiosityMethod, FurnaceProgressiveWithSubstructuring) {
  expect_furnace(R"({"patch_size": 1, "element_size": 0.5, "hemicube_resolution": 60, "threshold": 1e-4, "ambient": false})");
}

TEST(RadiosityMethod, FurnaceProgressiveWithAmbient) {
  // Stopped early, the ambient term of 000 §6.6.2 stands in for what is left unshot.
  expect_furnace(R"({"patch_size": 1, "element_size": 0.5, "hemicube_resolution": 60, "threshold": 0.002, "ambient": true})");
}

TEST(RadiosityMethod, FurnaceGaussSeidel) {
  expect_furnace(R"({"solver": "gauss-seidel", "patch_size": 1, "element_size": 0.5, "hemicube_resolution": 60, "threshold": 1e-6})");
}

TEST(RadiosityMethod, FurnaceGaussianElimination) {
  expect_furnace(R"({"solver": "gaussian", "patch_size": 1, "element_size": 0.5, "hemicube_resolution": 60})");
}

TEST(RadiosityMethod, FurnaceProgressiveWithRayCastFormFactors) {
  expect_furnace(R"({"form_factors": "ray-cast", "ray_cast_samples": 3, "patch_size": 1, "element_size": 0.5, "threshold": 1e-4, "ambient": false})");
}

TEST(RadiosityMethod, FurnaceGaussianWithRayCastFormFactors) {
  expect_furnace(R"({"solver": "gaussian", "form_factors": "ray-cast", "patch_size": 1, "element_size": 0.5})");
}

TEST(RadiosityMethod, SettingsAreCheckedAndUnknownKeysRefused) {
  const auto load = [](const std::string& radiosity) { return scene_from(furnace_scene(radiosity), kFurnaceCamera); };
  EXPECT_EQ(load("{}")->radiosity.hemicube_resolution, 100);
  EXPECT_EQ(load("{}")->radiosity.solver, RadiositySolver::progressive);
  EXPECT_EQ(load(R"({"solver": "gaussian"})")->radiosity.solver, RadiositySolver::gaussian);
  EXPECT_EQ(load("{}")->radiosity.form_factors, RadiosityFormFactors::hemicube);
  EXPECT_EQ(load(R"({"form_factors": "ray-cast"})")->radiosity.form_factors, RadiosityFormFactors::ray_cast);
  EXPECT_THROW(load(R"({"ray_cast_samples": 0})"), std::exception);
  EXPECT_THROW(load(R"({"hemicube_resolution": 51})"), std::exception);
  EXPECT_THROW(load(R"({"hemicube_resolution": 0})"), std::exception);
  EXPECT_THROW(load(R"({"threshold": 0})"), std::exception);
  EXPECT_THROW(load(R"({"solver": "jacobi"})"), std::exception);
  EXPECT_THROW(load(R"({"form_factors": "analytic"})"), std::exception);
  EXPECT_THROW(load(R"({"patch_size": 1, "element_size": 2})"), std::exception);
  EXPECT_THROW(load(R"({"patch_sise": 1})"), std::exception);
}

Film render_cornell_box(const Scene& scene, int threads, RunStatistics& statistics) {
  return testing::render_scene(scene, "radiosity", static_cast<std::size_t>(threads), statistics);
}

TEST(RadiosityMethod, CornellBoxConvergesAndDoesNotDependOnThreads) {
  const auto scene = load_scene_file(std::string(CANDELA_SOURCE_DIR) + "/scenes/cornell-box.json",
                                     {"camera.width=40", "camera.height=40", "radiosity.hemicube_resolution=50",
                                      "radiosity.threshold=0.01"});
  RunStatistics one_thread, two_threads;
  const Film a = render_cornell_box(*scene, 1, one_thread);
  const Film b = render_cornell_box(*scene, 2, two_threads);
  const auto& facts = one_thread.extra["radiosity"];
  EXPECT_LE(facts["unshot_fraction"].get<double>(), 0.01);
  EXPECT_TRUE(facts["converged"].get<bool>());
  EXPECT_GT(facts["steps"].get<int>(), 1);
  EXPECT_GT(facts["elements"].get<int>(), facts["patches"].get<int>());
  for (int y = 0; y < a.height(); ++y)
    for (int x = 0; x < a.width(); ++x) {
      EXPECT_EQ(a.at(x, y).r, b.at(x, y).r);
      EXPECT_EQ(a.at(x, y).g, b.at(x, y).g);
      EXPECT_EQ(a.at(x, y).b, b.at(x, y).b);
    }
  // Colour bleeding (000 §6.8): the floor near the red wall is redder than near the blue wall.
  const RadiositySolveResult result = solve_radiosity(*scene, true);
  Color near_red, near_blue;
  for (std::size_t q = 0; q < result.mesh.elements.size(); ++q) {
    const auto& element = result.mesh.elements[q];
    if (element.primitive != 0) continue;  // the floor
    if (element.centroid.x < 1) near_red += result.element_radiosity[q];
    if (element.centroid.x > 9) near_blue += result.element_radiosity[q];
  }
  EXPECT_GT(near_red.r / near_red.b, near_blue.r / near_blue.b);
}

// 000 §6.5, SPEC §10 "Display": the radiosity.display setting, "gouraud" by default.
TEST(RadiosityDisplay, SettingDefaultsToGouraudAndIsChecked) {
  const auto load = [](const std::string& radiosity) { return scene_from(furnace_scene(radiosity), kFurnaceCamera); };
  EXPECT_EQ(load("{}")->radiosity.display, RadiosityDisplay::gouraud);
  EXPECT_EQ(load(R"({"display": "flat"})")->radiosity.display, RadiosityDisplay::flat);
  EXPECT_EQ(load(R"({"display": "gouraud"})")->radiosity.display, RadiosityDisplay::gouraud);
  EXPECT_THROW(load(R"({"display": "phong"})"), std::exception);
}

// A constant field stays constant: every vertex of the furnace gets E / (1 − ρ) too.
TEST(RadiosityDisplay, FurnaceGouraudShowsEOverOneMinusRhoEverywhere) {
  expect_furnace(R"({"display": "gouraud", "patch_size": 1, "element_size": 0.5, "hemicube_resolution": 60, "threshold": 1e-4, "ambient": false})");
  expect_furnace(R"({"display": "gouraud", "solver": "gaussian", "patch_size": 1, "element_size": 0.5, "hemicube_resolution": 60})");
}

TEST(RadiosityDisplay, FurnaceFlatShowsEOverOneMinusRhoEverywhere) {
  expect_furnace(R"({"display": "flat", "patch_size": 1, "element_size": 0.5, "hemicube_resolution": 60, "threshold": 1e-4, "ambient": false})");
}

// The sum of squared differences between horizontally adjacent pixels in the image's bottom rows
// (the floor between the two boxes): a field with element steps concentrates its change in a few
// large jumps, a smooth one spreads it over many small ones (same total change, smaller squares).
double floor_steps(const Film& film) {
  double total = 0;
  for (int y = film.height() * 5 / 6; y < film.height(); ++y)
    for (int x = film.width() * 3 / 8; x + 1 < film.width() * 9 / 16; ++x) {
      const Color d = film.at(x + 1, y) - film.at(x, y);
      total += d.r * d.r + d.g * d.g + d.b * d.b;
    }
  return total;
}

TEST(RadiosityDisplay, CornellBoxGouraudHasNoElementStepsAndDoesNotDependOnThreads) {
  const std::vector<std::string> settings{"camera.width=64", "camera.height=64", "radiosity.hemicube_resolution=50",
                                          "radiosity.threshold=0.01"};
  const std::string file = std::string(CANDELA_SOURCE_DIR) + "/scenes/cornell-box.json";
  auto flat_settings = settings, gouraud_settings = settings;
  flat_settings.push_back("radiosity.display=\"flat\"");
  gouraud_settings.push_back("radiosity.display=\"gouraud\"");
  const auto flat_scene = load_scene_file(file, flat_settings);
  const auto gouraud_scene = load_scene_file(file, gouraud_settings);
  RunStatistics statistics;
  const Film flat = render_cornell_box(*flat_scene, 2, statistics);
  const Film one_thread = render_cornell_box(*gouraud_scene, 1, statistics);
  const Film two_threads = render_cornell_box(*gouraud_scene, 2, statistics);
  EXPECT_EQ(statistics.extra["radiosity"]["display"], "gouraud");
  for (int y = 0; y < one_thread.height(); ++y)
    for (int x = 0; x < one_thread.width(); ++x) {
      EXPECT_EQ(one_thread.at(x, y).r, two_threads.at(x, y).r);
      EXPECT_EQ(one_thread.at(x, y).g, two_threads.at(x, y).g);
      EXPECT_EQ(one_thread.at(x, y).b, two_threads.at(x, y).b);
    }
  const double flat_steps = floor_steps(flat), gouraud_steps = floor_steps(one_thread);
  RecordProperty("flat_steps", std::to_string(flat_steps));
  RecordProperty("gouraud_steps", std::to_string(gouraud_steps));
  EXPECT_GT(flat_steps, 0);
  EXPECT_LT(gouraud_steps, 0.5 * flat_steps);  // measured: 0.0071 against 0.0162
}

}  // namespace
}  // namespace candela
