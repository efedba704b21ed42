// Tests of the rectangular area light (scene/area_light.h), against the point-to-polygon form
// factor of radiosity/ and through the local method of integrators/.
#include "scene/area_light.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "integrators/local.h"
#include "integrators/scene_loading.h"
#include "math/constants.h"
#include "radiosity/ray_cast_form_factors.h"

namespace candela {
namespace {

// Σ_k intensity_k · max(0, n·L_k): the irradiance the samples give a point facing n.
double irradiance(const Light& light, const Vec3& x, const Vec3& n) {
  double sum = 0;
  for (int k = 0; k < light.sample_count(); ++k) {
    LightSample sample;
    if (light.illuminate_sample(x, k, {0.5, 0.5}, sample))
      sum += sample.intensity.g * std::max(0.0, dot(n, sample.direction));
  }
  return sum;
}

TEST(AreaLight, IrradianceIsTheExitanceTimesThePointToPolygonFormFactor) {
  // A unit square at height 1 facing down, exitance 3; by Lambert the irradiance at x is E·F(x → light).
  const AreaLight light({0, 0, 1}, {0, 1, 0}, {1, 0, 0}, Color(3.0), 16, false);
  EXPECT_EQ(light.sample_count(), 256);
  const std::vector<Vec3> square{{0, 0, 1}, {0, 1, 1}, {1, 1, 1}, {1, 0, 1}};  // wound to face down
  for (const Vec3& x : {Vec3{0.5, 0.5, 0}, Vec3{0.1, 0.8, 0}, Vec3{2, -1, 0.3}}) {
    const double exact = 3 * point_to_polygon_form_factor(x, {0, 0, 1}, square);
    EXPECT_NEAR(irradiance(light, x, {0, 0, 1}), exact, 0.01 * exact) << x.x;
  }
  // The centre answer carries all of it: (E/π) A / d² on the axis, far away.
  LightSample centre;
  ASSERT_TRUE(light.illuminate({0.5, 0.5, -99}, centre));
  EXPECT_NEAR(centre.intensity.g, 3 * kInvPi / (100.0 * 100.0), 1e-15);
  // Behind it: nothing, unless two-sided.
  LightSample behind;
  EXPECT_FALSE(light.illuminate_sample({0.5, 0.5, 2}, 0, {0.5, 0.5}, behind));
  EXPECT_FALSE(light.illuminate({0.5, 0.5, 2}, behind));
  const AreaLight both({0, 0, 1}, {0, 1, 0}, {1, 0, 0}, Color(3.0), 4, true);
  EXPECT_TRUE(both.illuminate_sample({0.5, 0.5, 2}, 0, {0.5, 0.5}, behind));
  EXPECT_FALSE(light.illuminate_sample({0.5, 0.5, 0}, 256, {0.5, 0.5}, behind));  // no such sample
  EXPECT_THROW(AreaLight({0, 0, 0}, {1, 0, 0}, {2, 0, 0}, Color(1.0), 4, false), std::invalid_argument);
  EXPECT_THROW(AreaLight({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, Color(1.0), 0, false), std::invalid_argument);
}

std::unique_ptr<Scene> lit_floor(const std::string& extra_shapes) {
  return load_scene_text(R"({"format": "candela/1",
    "camera": {"eye": [0, 0, 8], "target": [0, 0, 0], "fov": 40, "width": 32, "height": 32},
    "lights": [{"type": "area", "corner": [-0.5, -0.5, 2], "edge_u": [0, 1, 0], "edge_v": [1, 0, 0], "exitance": 5, "samples": 8}],
    "shapes": [{"type": "quad", "corner": [-4, -4, 0], "edge_u": [8, 0, 0], "edge_v": [0, 8, 0], "material": {"kd": 0.5, "ks": 0}})" +
                             extra_shapes + "]}",
                         "floor.json", ".");
}

TEST(AreaLight, LocalModelShowsKdTimesIrradianceAndSoftShadows) {
  const auto scene = lit_floor("");
  EXPECT_EQ(scene->lights.front()->type_name(), "area");
  // The pixel at the image centre looks at (0, 0, 0), straight under the light.
  Color centre;
  LocalMethod().pixel_ray_tree(*scene, 16, 16, centre);
  const std::vector<Vec3> square{{-0.5, -0.5, 2}, {-0.5, 0.5, 2}, {0.5, 0.5, 2}, {0.5, -0.5, 2}};
  const Ray ray = scene->camera->generate_ray(16.5, 16.5);
  const Vec3 hit_point = ray.at(-ray.origin.z / ray.direction.z);  // where it meets the floor z = 0
  const double exact =
      0.5 * 5 * point_to_polygon_form_factor({hit_point.x, hit_point.y, 0}, {0, 0, 1}, square);
  EXPECT_NEAR(centre.g, exact, 0.01 * exact);
  // A small blocker halfway up, off to the side so that the camera sees past it: the floor in its
  // shadow (pixel 22 looks at x ≈ 1.18, where the blocker hides part of the light from) is darker
  // than without it but not black (penumbra from the light's other samples), and the floor on the
  // other side is as bright as before.
  const auto shadowed = lit_floor(
      R"(, {"type": "quad", "corner": [0.45, -0.15, 1], "edge_u": [0.3, 0, 0], "edge_v": [0, 0.3, 0]})");
  Color open, under, far_open, far_blocked;
  LocalMethod().pixel_ray_tree(*scene, 22, 16, open);
  LocalMethod().pixel_ray_tree(*shadowed, 22, 16, under);
  LocalMethod().pixel_ray_tree(*scene, 6, 16, far_open);
  LocalMethod().pixel_ray_tree(*shadowed, 6, 16, far_blocked);
  EXPECT_LT(under.g, 0.9 * open.g);
  EXPECT_GT(under.g, 0.1 * open.g);
  EXPECT_EQ(far_blocked.g, far_open.g);
}

TEST(AreaLight, BadInputIsALocatedError) {
  EXPECT_THROW(
      load_scene_text(
          R"({"format": "candela/1", "lights": [{"type": "area", "corner": [0, 0, 0], "edge_u": [1, 0, 0], "edge_v": [2, 0, 0]}]})",
          "bad.json", "."),
      std::exception);
  EXPECT_THROW(
      load_scene_text(
          R"({"format": "candela/1", "lights": [{"type": "area", "corner": [0, 0, 0], "edge_u": [1, 0, 0], "edge_v": [0, 1, 0], "samples": 0}]})",
          "bad.json", "."),
      std::exception);
}

}  // namespace
}  // namespace candela
