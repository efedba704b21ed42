#include "integrators/whitted.h"

#include <gtest/gtest.h>

#include <cmath>
#include <regex>

#include "integrators/local.h"
#include "integrators/ray_tree.h"
#include "integrators/scene_loading.h"
#include "scene_text.h"

namespace candela {
namespace {

using testing::kCentreCamera;
using testing::scene_from;

// The method as the scene's "whitted" object makes it.
WhittedMethod whitted_of(const Scene& scene) {
  return WhittedMethod(read_whitted_settings(scene.plugin_settings.node("whitted")));
}

Color render_pixel(const Scene& scene, const RayTracingMethod& method) {
  Color radiance;
  method.pixel_ray_tree(scene, 0, 0, radiance);
  return radiance;
}

TEST(Whitted, LocalModelOnALitPlaneMatchesTheFormula) {
  // Plane z = 0 facing the eye, point light at (0, 3, 4) with linear attenuation d0 = 1:
  // I = ka·Ia + Ip/(d + d0)·[kd(N·L) + ks(R·V)^n]
  const auto scene = scene_from(R"(
    "ambient": 0.2,
    "lights": [{"type": "point", "position": [0, 3, 4], "intensity": 2, "attenuation": {"mode": "linear", "d0": 1}}],
    "materials": {"m": {"kd": [0.5, 0.25, 1], "ka": 0.1, "ks": 0.3, "n": 2}},
    "shapes": [{"type": "plane", "point": [0, 0, 0], "normal": [0, 0, 1], "material": "m"}])",
                                kCentreCamera);
  const double d = 5, n_dot_l = 0.8;
  // R = 2N(N·L) − L = (0, -0.6, 0.8); V = (0, 0, 1): R·V = 0.8.
  const double specular = 0.3 * 0.8 * 0.8;
  const Color expected =
      Color(0.1 * 0.2) + Color(0.5, 0.25, 1) * (2 / (d + 1) * n_dot_l) + Color(2 / (d + 1) * specular);
  const Color got = render_pixel(*scene, whitted_of(*scene));
  EXPECT_NEAR(got.r, expected.r, 1e-12);
  EXPECT_NEAR(got.g, expected.g, 1e-12);
  EXPECT_NEAR(got.b, expected.b, 1e-12);
}

TEST(Whitted, AttenuationModes) {
  const std::string shapes =
      R"("shapes": [{"type": "plane", "point": [0, 0, 0], "normal": [0, 0, 1], "material": {"kd": 1}}])";
  const auto with = [&](const std::string& attenuation) {
    const auto scene = scene_from(R"("lights": [{"type": "point", "position": [0, 0, 4], "attenuation": )" +
                                      attenuation + "}], " + shapes,
                                  kCentreCamera);
    return render_pixel(*scene, whitted_of(*scene)).r;
  };
  EXPECT_NEAR(with("\"none\""), 1.0, 1e-12);
  EXPECT_NEAR(with("\"inverse-square\""), 1.0 / (4 * kPi * 16), 1e-12);
  EXPECT_NEAR(with(R"({"mode": "linear", "d0": 2})"), 1.0 / 6, 1e-12);
  EXPECT_NEAR(with(R"({"mode": "polynomial", "constant": 1, "linear": 0.5, "quadratic": 0.25})"), 1.0 / 7,
              1e-12);
  // Clamped at 1: a small denominator never amplifies (001's f_at ≤ 1).
  EXPECT_NEAR(with(R"({"mode": "polynomial", "constant": 0.1})"), 1.0, 1e-12);
}

TEST(Whitted, OpaqueOccluderCastsAShadowAndTransparentOneIsAttenuatedByKt) {
  const std::string base = R"(
    "lights": [{"type": "point", "position": [0, 0, 8]}],
    "materials": {"floor": {"kd": 1}, "blocker": {"kd": 0, "kt": KT}},
    "shapes": [{"type": "plane", "point": [0, 0, 0], "normal": [0, 0, 1], "material": "floor"},
               {"type": "polygon", "vertices": [[-1, -1, 4], [1, -1, 4], [1, 1, 4], [-1, 1, 4]], "material": "blocker"}])";
  // The camera looks from the side so the primary ray does not cross the blocker.
  const char* side = R"({"eye": [3, 0, 1], "target": [0, 0, 0], "fov": 0.5, "width": 1, "height": 1})";
  const auto opaque = scene_from(std::regex_replace(base, std::regex("KT"), "0"), side);
  EXPECT_TRUE(render_pixel(*opaque, whitted_of(*opaque)).is_black());
  const auto glass = scene_from(std::regex_replace(base, std::regex("KT"), "0.6"), side);
  const auto open = scene_from(std::regex_replace(base, std::regex("KT"), "1"), side);
  const double lit = render_pixel(*open, whitted_of(*open)).r;
  EXPECT_GT(lit, 0);
  EXPECT_NEAR(render_pixel(*glass, whitted_of(*glass)).r, 0.6 * lit, 1e-12);
}

// Without a material that lets light through, shadow rays only ask the accelerator whether
// anything lies on their segment (Scene::occluded); with the ray tree recorded, or with glass in
// the scene, they walk the crossings. Both give the same radiance and the same shadow-ray count.
TEST(Whitted, ShadowRaysOfAnOpaqueSceneAskOnlyWhetherAnythingIsInTheWay) {
  const std::string base = R"(
    "lights": [{"type": "point", "position": [0, 0, 8]}, {"type": "point", "position": [6, 0, 8]}],
    "materials": {"floor": {"kd": 1, "ks": 0.3, "n": 8}, "blocker": {"kd": 0.5, "kt": KT}},
    "shapes": [{"type": "plane", "point": [0, 0, 0], "normal": [0, 0, 1], "material": "floor"},
               {"type": "polygon", "vertices": [[-1, -1, 4], [1, -1, 4], [1, 1, 4], [-1, 1, 4]], "material": "blocker"}])";
  const char* side = R"({"eye": [3, 0, 1], "target": [0, 0, 0], "fov": 0.5, "width": 1, "height": 1})";
  for (const std::string kt : {"0", "0.6"}) {
    const auto scene = scene_from(std::regex_replace(base, std::regex("KT"), kt), side);
    EXPECT_EQ(scene->lets_light_through(), kt != "0");
    const WhittedMethod method = whitted_of(*scene);
    // Floor points in the blocker's shadow from one light, from both, and from neither.
    for (const Vec3 target : {Vec3{0, 0, 0}, Vec3{0.4, 0.2, 0}, Vec3{2.5, 0, 0}, Vec3{-3, 0.5, 0}}) {
      const Ray ray{Vec3{3, 0, 1}, normalize(target - Vec3{3, 0, 1})};
      TraceContext plain;
      const Color asked = method.trace_primary(*scene, ray, plain);
      RayTree tree;
      TraceContext recorded;
      recorded.tree = &tree;
      const Color walked = method.trace_primary(*scene, ray, recorded);
      EXPECT_EQ(asked, walked) << kt << " " << target.x;
      EXPECT_EQ(plain.counts.shadow, recorded.counts.shadow);
      EXPECT_GT(plain.counts.shadow, 0u);
    }
  }
}

TEST(Whitted, AbsorptionDarkensLongerPathsThroughGlass) {
  // A glass sphere of radius 1 at height 2 above the floor, light straight above: the shadow
  // ray from the floor point below the centre crosses 2 units of glass, one from an
  // off-centre point crosses 2·sqrt(1 − x²).
  const std::string body = R"(
    "lights": [{"type": "directional", "direction": [0, 0, -1]}],
    "materials": {"floor": {"kd": 1}, "glass": {"kd": 0, "kt": 0.9, "ior": 1.5, "absorption": 0.5}},
    "shapes": [{"type": "plane", "point": [0, 0, 0], "normal": [0, 0, 1], "material": "floor"},
               {"type": "sphere", "center": [0, 0, 2], "radius": 1, "material": "glass"}])";
  const auto at = [&](double x) {
    const std::string camera = R"({"eye": [)" + std::to_string(x) + R"(, -3, 0.5], "target": [)" +
                               std::to_string(x) + R"(, 0, 0], "fov": 0.01, "width": 1, "height": 1})";
    const auto scene = scene_from(body, camera);
    return render_pixel(*scene, LocalMethod());
  };
  // The camera ray hits the floor at y slightly off 0; use the analytic chord at its hit.
  const double centre = at(0).r, off = at(0.6).r;
  EXPECT_NEAR(centre, 0.9 * std::exp(-0.5 * 2.0), 2e-3);
  EXPECT_NEAR(off, 0.9 * std::exp(-0.5 * 2.0 * std::sqrt(1 - 0.36)), 2e-3);
  EXPECT_LT(centre, off);
}

TEST(Whitted, LightInsideAnAbsorbingSphere) {
  // A point light at the centre of a glass sphere (radius 0.5, kt 0.9, absorption 5): the
  // shadow ray from outside crosses 0.5 of glass, s = 0.9·exp(−2.5). It used to skip the
  // absorption because the ray never left the sphere before reaching the light.
  const auto scene =
      scene_from(R"(
    "lights": [{"type": "point", "position": [0, 0, 2]}],
    "materials": {"floor": {"kd": 1}, "glass": {"kd": 0, "kt": 0.9, "absorption": 5}},
    "shapes": [{"type": "plane", "point": [0, 0, 0], "normal": [0, 0, 1], "material": "floor"},
               {"type": "sphere", "center": [0, 0, 2], "radius": 0.5, "material": "glass"}])",
                 R"({"eye": [3, 0, 0.5], "target": [0, 0, 0], "fov": 0.001, "width": 1, "height": 1})");
  Color radiance;
  const RayTree tree = LocalMethod().pixel_ray_tree(*scene, 0, 0, radiance);
  ASSERT_EQ(tree.nodes().size(), 2u);
  EXPECT_NEAR(tree.nodes()[1].transmittance.r, 0.9 * std::exp(-2.5), 1e-6);
}

TEST(Whitted, SmallShadowsSurviveFarFromTheOrigin) {
  // A 3 mm ball 6 mm above the floor shades the floor point below it, at x = 0 and at
  // x = 1e5 alike. The offset used to scale with the coordinates (1e-7 × 1e5 = 1 cm) and
  // start the shadow ray above the ball.
  for (const double x : {0.0, 1e5}) {
    const std::string X = std::to_string(x);
    const auto scene = scene_from(R"(
      "lights": [{"type": "point", "position": [)" +
                                      X + R"(, 0, 1]}],
      "shapes": [{"type": "plane", "point": [0, 0, 0], "normal": [0, 0, 1]},
                 {"type": "sphere", "center": [)" +
                                      X + R"(, 0, 0.006], "radius": 0.003}])",
                                  R"({"eye": [)" + X + R"(, -0.05, 0.0001], "target": [)" + X +
                                      R"(, 0, 0], "fov": 0.001, "width": 1, "height": 1})");
    EXPECT_TRUE(render_pixel(*scene, LocalMethod()).is_black()) << "x = " << x;
  }
}

TEST(Whitted, MirrorReflectionAndDepth) {
  // Eye looks at a mirror (kr 0.9, kd 0) that faces it; behind the eye is a red wall lit by
  // ambient light only. Depth 0: the mirror is black (000 Figure 51); depth 1: 0.9 × red.
  const std::string body = R"(
    "ambient": 1,
    "materials": {"mirror": {"kd": 0, "kr": 0.9}, "red": {"kd": [1, 0, 0]}},
    "shapes": [{"type": "plane", "point": [0, 0, 0], "normal": [0, 0, 1], "material": "mirror"},
               {"type": "plane", "point": [0, 0, 20], "normal": [0, 0, -1], "material": "red"}],
    "whitted": {"max_depth": DEPTH})";
  const auto depth = [&](int d) {
    return scene_from(std::regex_replace(body, std::regex("DEPTH"), std::to_string(d)), kCentreCamera);
  };
  EXPECT_TRUE(render_pixel(*depth(0), whitted_of(*depth(0))).is_black());
  const Color one = render_pixel(*depth(1), whitted_of(*depth(1)));
  EXPECT_NEAR(one.r, 0.9, 1e-12);
  EXPECT_NEAR(one.g, 0, 1e-12);
}

TEST(Whitted, TwoFacingMirrorsDarkenGeometrically) {
  // Two parallel mirrors with kr = 0.5 and a background of 1 visible through neither: the
  // ray bounces until max_depth; every level adds nothing but the last reaches no light, so
  // the radiance is 0 — while the adaptive threshold stops the tree early: with
  // min_weight 0.1 the tree holds 1 + 3 rays (0.5, 0.25, 0.125 ≥ 0.1; 0.0625 < 0.1).
  const auto scene = scene_from(R"(
    "background": 1,
    "materials": {"mirror": {"kd": 0, "kr": 0.5}},
    "shapes": [{"type": "plane", "point": [0, 0, 0], "normal": [0, 0, 1], "material": "mirror"},
               {"type": "plane", "point": [0, 0, 20], "normal": [0, 0, -1], "material": "mirror"}],
    "whitted": {"max_depth": 50, "min_weight": 0.1})",
                                kCentreCamera);
  Color radiance;
  const RayTree tree = whitted_of(*scene).pixel_ray_tree(*scene, 0, 0, radiance);
  EXPECT_EQ(tree.nodes().size(), 4u);
  EXPECT_NE(tree.nodes().back().note.find("pruned"), std::string::npos);
  EXPECT_TRUE(radiance.is_black());
}

TEST(Whitted, RefractionThroughASlabKeepsTheDirection) {
  // A glass box (kt 1, ior 1.5) between the eye and a lit white plane: the ray enters and
  // leaves through parallel faces, so it continues along its original line and sees the
  // plane's color times kt².
  const auto scene =
      scene_from(R"(
    "ambient": 1,
    "materials": {"glass": {"kd": 0, "kt": 0.8, "ior": 1.5}, "white": {"kd": 1}},
    "shapes": [{"type": "box", "min": [-5, -5, 2], "max": [5, 5, 4], "material": "glass"},
               {"type": "plane", "point": [0, 0, 0], "normal": [0, 0, 1], "material": "white"}])",
                 R"({"eye": [0.3, 0.2, 10], "target": [0, 0, 0], "fov": 0.01, "width": 1, "height": 1})");
  Color radiance;
  const RayTree tree = whitted_of(*scene).pixel_ray_tree(*scene, 0, 0, radiance);
  EXPECT_NEAR(radiance.r, 0.64, 1e-9);
  // The ray that reaches the plane leaves the box parallel to the primary ray.
  const RayTreeNode& primary = tree.nodes().front();
  const RayTreeNode& last = tree.nodes().back();
  EXPECT_EQ(last.kind, RayKind::refracted);
  EXPECT_NEAR(dot(last.direction, primary.direction), 1.0, 1e-12);
}

TEST(Whitted, TotalInternalReflectionInsideGlass) {
  // Looking from inside a glass block (ior 1.5) at its top face at 60° from the normal, past
  // the critical angle of 41.8°: the tree holds an internal reflection, not a refraction.
  const auto scene = scene_from(
      R"(
    "materials": {"glass": {"kd": 0, "kt": 1, "ior": 1.5}},
    "shapes": [{"type": "box", "min": [-100, -100, -100], "max": [100, 100, 0], "material": "glass"}],
    "whitted": {"max_depth": 1})",
      R"({"eye": [0, 0, -1], "target": [0.8660254037844386, 0, -0.5], "fov": 0.01, "width": 1, "height": 1})");
  Color radiance;
  const RayTree tree = whitted_of(*scene).pixel_ray_tree(*scene, 0, 0, radiance);
  ASSERT_EQ(tree.nodes().size(), 2u);
  EXPECT_EQ(tree.nodes()[1].kind, RayKind::internal_reflection);
  EXPECT_NEAR(tree.nodes()[1].direction.z, -0.5, 1e-9);
}

TEST(Whitted, NoShadowAcneOnCurvedSurfaces) {
  // A lit sphere seen from the light's side: every pixel that sees the sphere must be lit
  // (no self-shadowing speckles), at several scene scales.
  for (double scale : {1e-3, 1.0, 1e4}) {
    const std::string s = std::to_string(scale);
    const auto scene = scene_from(R"("lights": [{"type": "point", "position": [0, 0, )" +
                                      std::to_string(10 * scale) + R"(]}],
           "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": )" +
                                      s + "}]",
                                  R"({"eye": [0, 0, )" + std::to_string(5 * scale) +
                                      R"(], "target": [0, 0, 0], "fov": 15, "width": 32, "height": 32})");
    const Film film = whitted_of(*scene).render(*scene, {{0, 0, 32, 32}, true}).film;
    int dark = 0, lit = 0;
    for (const Color& c : film.pixels()) {
      if (c.r > 0)
        ++lit;
      else
        ++dark;
    }
    // The sphere subtends 23° of the 15° view (21° at the corners) at this distance: it fills the image.
    EXPECT_EQ(dark, 0) << "scale " << scale;
    EXPECT_EQ(lit, 32 * 32);
  }
}

}  // namespace
}  // namespace candela
