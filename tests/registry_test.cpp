// Every registered name can be created from its documented example (STYLE.md habit 2).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <set>

#include "accel/accelerator_registry.h"
#include "integrators/method_registry.h"
#include "integrators/probe.h"
#include "integrators/scene_loading.h"
#include "io/image_writer.h"
#include "scene/camera_registry.h"
#include "scene/light_registry.h"
#include "scene/material_registry.h"
#include "scene/shape_registry.h"
#include "scratch_directory.h"

namespace candela {
namespace {

class RegistryTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::filesystem::create_directories(directory_ / "meshes");
    std::filesystem::create_directories(directory_ / "textures");
    std::filesystem::create_directories(directory_ / "luminaires");
    std::ofstream(directory_ / "luminaires" / "downlight.ies")
        << "IESNA:LM-63-2002\nTILT=NONE\n1 -1 1 3 1 1 2 0 0 0\n1 1 10\n0 45 90\n0\n100 70 0\n";
    Film checker(4, 4);
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 4; ++x) checker.at(x, y) = Color((x + y) % 2 ? 0.9 : 0.1);
    write_png(checker, (directory_ / "textures" / "checker.png").string(), DisplaySettings{});
    std::ofstream cube(directory_ / "meshes" / "cube.obj");
    cube << "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
            "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";
  }

  std::unique_ptr<Scene> load(const std::string& body) {
    return load_scene_text(R"({"format": "candela/1", "camera": {"width": 8, "height": 6}, )" + body + "}",
                           "registry.json", directory_.string());
  }
  candela::testing::ScratchDirectory scratch_{"candela-registry"};
  const std::filesystem::path& directory_ = scratch_.path();
};

TEST_F(RegistryTest, EveryShapeFromItsExample) {
  std::set<std::string_view> names;
  for (const ShapeEntry& entry : shape_entries()) {
    EXPECT_TRUE(names.insert(entry.name).second) << "duplicate " << entry.name;
    const auto scene = load(R"("shapes": [)" + std::string(entry.example) + "]");
    ASSERT_EQ(scene->objects.size(), 1u) << entry.name;
    EXPECT_EQ(scene->objects[0].type, entry.name);
    EXPECT_GE(scene->primitives.size(), 1u) << entry.name;
    EXPECT_EQ(find_shape(entry.name), &entry);
  }
  EXPECT_EQ(find_shape("teapot"), nullptr);
}

TEST_F(RegistryTest, EveryLightFromItsExample) {
  for (const LightEntry& entry : light_entries()) {
    const auto scene = load(R"("lights": [)" + std::string(entry.example) + "]");
    if (entry.name == "ambient") {
      EXPECT_TRUE(scene->lights.empty());
      EXPECT_FALSE(scene->ambient.is_black());
    } else {
      ASSERT_EQ(scene->lights.size(), 1u) << entry.name;
      EXPECT_EQ(scene->lights[0]->type_name(), entry.name);
    }
  }
}

TEST_F(RegistryTest, EveryMaterialAndTextureFromItsExample) {
  for (const MaterialEntry& entry : material_entries()) {
    const auto scene = load(R"("materials": {"m": )" + std::string(entry.example) + "}");
    EXPECT_EQ(scene->materials.back().name, "m");
  }
  for (const MappingEntry& entry : mapping_entries()) {
    const auto scene = load(R"("materials": {"m": {"kd": {"type": "checker2d", "mapping": )" +
                            std::string(entry.example) + "}}}");
    const auto& texture = dynamic_cast<const Texture2D&>(*scene->materials.back().kd);
    EXPECT_EQ(texture.mapping().type_name(), entry.name);
    EXPECT_EQ(find_mapping(entry.name), &entry);
  }
  for (const TextureEntry& entry : texture_entries()) {
    const auto scene = load(R"("materials": {"m": {"kd": )" + std::string(entry.example) + "}}");
    EXPECT_EQ(scene->materials.back().kd->type_name(), entry.name);
  }
}

TEST_F(RegistryTest, EveryCameraFromItsExample) {
  for (const CameraEntry& entry : camera_entries()) {
    const auto scene =
        load_scene_text(R"({"format": "candela/1", "camera": )" + std::string(entry.example) + "}",
                        "registry.json", directory_.string());
    EXPECT_EQ(scene->camera->type_name(), entry.name);
    EXPECT_EQ(scene->camera->width(), 320);
  }
}

TEST_F(RegistryTest, EveryMethodAndAccelerator) {
  for (const MethodEntry& entry : method_entries()) {
    // aa.mode "none": the default scene's adaptive anti-aliasing is not every method's.
    const auto method = create_method(entry, *load_default_scene({"aa.mode=none", "aa.filter=box"}));
    EXPECT_EQ(method->name(), entry.name);
  }
  EXPECT_EQ(find_method("raytrace"), nullptr);
  for (const AcceleratorEntry& entry : accelerator_entries()) {
    const auto accelerator = create_default_accelerator(entry);
    EXPECT_EQ(accelerator->name(), entry.name);
  }
}

// A method answers for itself: whatever its capabilities promise, it gives (probe), and the keys
// that say only how far it runs are its own, so no caller spells them.
TEST_F(RegistryTest, MethodsAnswerForThemselves) {
  const auto scene =
      load_default_scene({"aa.mode=none", "aa.filter=box", "camera.width=8", "camera.height=6"});
  ProbeSettings settings;
  settings.samples = 1;
  for (const MethodEntry& entry : method_entries()) {
    if (entry.capabilities.probe) continue;  // those solve now: probe_test.cpp probes each
    EXPECT_EQ(create_method(entry, *scene)->point_probe(*scene, settings), nullptr) << entry.name;
  }
  EXPECT_TRUE(find_method(kReferenceMethod)->capabilities.probe);
  EXPECT_TRUE(overrides_run_length("path.spp=16"));
  EXPECT_TRUE(overrides_run_length("path.checkpoint_interval=5"));
  EXPECT_TRUE(overrides_run_length("radiosity.threshold=1e-4"));
  EXPECT_FALSE(overrides_run_length("path.sampler=independent"));  // changes every sample
  EXPECT_FALSE(overrides_run_length("path.spp2=16"));
  EXPECT_FALSE(overrides_run_length("radiosity.solver=progressive"));
  EXPECT_FALSE(overrides_run_length("whitted.spp=16"));
  EXPECT_EQ(run_limit_overrides({16, std::nullopt, std::nullopt}), (std::vector<std::string>{"path.spp=16"}));
  EXPECT_EQ(run_limit_overrides({std::nullopt, 2.5, 10.0}),
            (std::vector<std::string>{"path.time=2.5", "path.spp=0", "path.checkpoint_interval=10"}));
}

}  // namespace
}  // namespace candela
