// The scene key "microfacet" (src/scene/material_registry.cpp) selecting the facet distribution
// of the Cook-Torrance lobe (src/shading/material_bsdf.h).
#include <gtest/gtest.h>

#include <string>

#include "integrators/scene_loading.h"
#include "scene/scene.h"
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

}  // namespace
}  // namespace candela
