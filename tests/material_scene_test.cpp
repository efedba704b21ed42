// The scene keys "microfacet" (src/scene/material_registry.cpp) selecting the facet distribution
// of the Cook-Torrance lobe (src/shading/material_bsdf.h), and fresnel_ior, fresnel_k and
// fresnel_f0 selecting its Fresnel factor (src/shading/fresnel.h) in the local model and the path
// tracer alike.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "integrators/scene_loading.h"
#include "math/constants.h"
#include "scene/scene.h"
#include "shading/local_model.h"
#include "shading/material_bsdf.h"
#include "util/error.h"

namespace candela {
namespace {

const char* kScene = R"({
  "format": "candela/1",
  "camera": {"eye": [0, 0, 5], "target": [0, 0, 0], "width": 4, "height": 3},
  "materials": {"m": MATERIAL},
  "shapes": [{"type": "sphere", "radius": 1, "material": "m"}]
})";

std::string scene_with(const std::string& material) {
  std::string text = kScene;
  text.replace(text.find("MATERIAL"), 8, material);
  return text;
}

TEST(MaterialBsdf, SceneKeyMicrofacet) {
  const auto ggx =
      load_scene_text(scene_with(R"({"type": "cook-torrance", "microfacet": "ggx"})"), "t.json", ".");
  EXPECT_EQ(ggx->materials[ggx->primitives[0].material].microfacet, MicrofacetDistribution::ggx);
  const auto fallback = load_scene_text(scene_with(R"({"type": "cook-torrance"})"), "t.json", ".");
  EXPECT_EQ(fallback->materials[fallback->primitives[0].material].microfacet,
            MicrofacetDistribution::beckmann);
  try {
    load_scene_text(scene_with(R"({"type": "cook-torrance", "microfacet": "phong"})"), "t.json", ".");
    ADD_FAILURE() << "a bad distribution loaded";
  } catch (const InputError& e) {
    EXPECT_EQ(e.location().file, "t.json");
    EXPECT_EQ(e.location().line, 4);
    EXPECT_NE(e.location().json_path.find("microfacet"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("beckmann, ggx"), std::string::npos) << e.what();
  }
  // Only the Cook-Torrance model has facets.
  EXPECT_THROW(load_scene_text(scene_with(R"({"type": "phong", "microfacet": "ggx"})"), "t.json", "."),
               InputError);
}

const Material& material_of(const Scene& scene) {
  return scene.materials[scene.primitives[0].material];
}

TEST(MaterialFresnel, SceneKeysChooseTheModel) {
  const auto glass = load_scene_text(scene_with(R"({"type": "cook-torrance", "ior": 1.7})"), "t.json", ".");
  EXPECT_TRUE(material_of(*glass).fresnel == Fresnel::dielectric(Color(1.7)));
  const auto metal = load_scene_text(
      scene_with(
          R"({"type": "cook-torrance", "fresnel_ior": [0.2, 0.9, 1.2], "fresnel_k": [3.7, 2.6, 2.4]})"),
      "t.json", ".");
  EXPECT_TRUE(material_of(*metal).fresnel == Fresnel::conductor(Color(0.2, 0.9, 1.2), Color(3.7, 2.6, 2.4)));
  const auto measured = load_scene_text(
      scene_with(R"({"type": "cook-torrance", "fresnel_f0": [0.95, 0.64, 0.54]})"), "t.json", ".");
  EXPECT_TRUE(material_of(*measured).fresnel == Fresnel::schlick(Color(0.95, 0.64, 0.54)));
  // The path tracer's lobe carries the same factor.
  SurfaceHit hit;
  hit.geometric_normal = hit.shading_normal = {0, 0, 1};
  const Material& copper = material_of(*measured);
  const Bsdf bsdf = make_bsdf(copper, copper.at(hit), hit, hit.shading_normal);
  ASSERT_EQ(bsdf.lobe_count(), 2);
  EXPECT_TRUE(bsdf.lobe(1).fresnel == copper.fresnel);

  for (const char* bad : {R"({"type": "cook-torrance", "fresnel_f0": 0.5, "fresnel_k": 1})",
                          R"({"type": "cook-torrance", "fresnel_ior": 0.5, "fresnel_k": -1})",
                          R"({"type": "cook-torrance", "fresnel_ior": 1.5, "fresnel_f0": 0.5})"}) {
    try {
      load_scene_text(scene_with(bad), "t.json", ".");
      ADD_FAILURE() << bad << " loaded";
    } catch (const InputError& e) {
      EXPECT_EQ(e.location().line, 4) << e.what();
      EXPECT_NE(e.location().json_path.find("fresnel_"), std::string::npos) << e.what();
    }
  }
}

// Copper given by its F0 turned bluish at grazing incidence in the local model — its
// derived real index had a Brewster dip (highlight [0.68, 0.55, 0.60]·DG at 87°). Now the
// highlight keeps copper's order of channels at every angle and each channel only rises.
TEST(MaterialFresnel, ACopperHighlightWhitensTowardGrazingIncidence) {
  const auto scene = load_scene_text(
      scene_with(
          R"({"type": "cook-torrance", "kd": 0, "ks": 1, "roughness": 0.3, "fresnel_f0": [0.95, 0.64, 0.54]})"),
      "t.json", ".");
  const Material& copper = material_of(*scene);
  SurfaceHit hit;
  hit.geometric_normal = hit.shading_normal = {0, 0, 1};
  const SurfaceProperties at = copper.at(hit);
  const Vec3 N{0, 0, 1};
  Color previous;
  for (int degrees = 0; degrees <= 88; ++degrees) {
    // V and L mirror each other about N = H, each at θ from it: F is taken at θ.
    const double theta = degrees * kPi / 180;
    const Vec3 V{std::sin(theta), 0, std::cos(theta)}, L{-std::sin(theta), 0, std::cos(theta)};
    const Color highlight = direct_term(copper, at, N, V, L, Color(1));
    // ks·(N·L)·F·D·G/(π(N·V)(N·L)) with N·H = 1: D = 1/m², G = min(1, 2(N·V)/(V·H)) = 1.
    const Color F = highlight * (kPi * std::cos(theta) * 0.09);
    EXPECT_GE(F.r, F.g) << degrees << "°";
    EXPECT_GE(F.g, F.b) << degrees << "°";
    for (int c = 0; c < 3; ++c) EXPECT_GE(F[c], previous[c] - 1e-12) << degrees << "° channel " << c;
    previous = F;
  }
  EXPECT_GT(previous.b, 0.85);
}

}  // namespace
}  // namespace candela
