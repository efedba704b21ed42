// Mesh files (src/io/*_import.cpp) loaded through a scene's "mesh" shape (src/scene/): the
// importers' results placed in the scene, and the extensions the shape accepts.
#include <gtest/gtest.h>

#include <string>

#include "integrators/scene_loading.h"
#include "io/mesh_test_files.h"
#include "scene/scene.h"
#include "scratch_directory.h"

namespace candela {
namespace {

using testing::glb;
using testing::kAsciiCube;
using testing::square_buffer;
using testing::square_json;
using testing::write_file;

TEST(GltfImport, LoadedSceneHasTheTriangles) {
  testing::ScratchDirectory scratch("gltf");
  write_file(scratch.path() / "square.glb", glb(square_json(""), square_buffer()));
  const auto scene = load_scene_text(R"({"format": "candela/1",
    "camera": {"eye": [0.5, 0.5, 3], "target": [0.5, 0.5, 0], "fov": 50, "width": 8, "height": 8},
    "shapes": [{"type": "mesh", "file": "square.glb", "material": {"kd": 0.5}}]})",
                                     "gltf.json", scratch.path().string());
  EXPECT_EQ(scene->primitives.size(), 2u);
  EXPECT_DOUBLE_EQ(scene->bounds().upper.x, 1.0);
  EXPECT_DOUBLE_EQ(scene->bounds().upper.y, 1.0);
}

TEST(PlyImport, LoadedSceneHasTheTriangles) {
  testing::ScratchDirectory scratch("ply");
  write_file(scratch.path() / "cube.ply", kAsciiCube);
  const auto scene = load_scene_text(R"({"format": "candela/1",
    "camera": {"eye": [3, 3, 3], "target": [0, 0, 0], "fov": 50, "width": 8, "height": 8},
    "shapes": [{"type": "mesh", "file": "cube.ply", "transform": [{"translate": [1, 0, 0]}],
                "material": {"kd": 0.5}}]})",
                                     "ply.json", scratch.path().string());
  EXPECT_EQ(scene->primitives.size(), 12u);
  EXPECT_DOUBLE_EQ(scene->bounds().lower.x, 1.0);
  EXPECT_DOUBLE_EQ(scene->bounds().upper.x, 2.0);
  EXPECT_DOUBLE_EQ(scene->bounds().upper.z, 1.0);
}

TEST(PlyImport, UnknownMeshExtensionIsRefused) {
  testing::ScratchDirectory scratch("ply");
  write_file(scratch.path() / "cube.stl", "solid");
  try {
    (void)load_scene_text(R"({"format": "candela/1",
      "camera": {"eye": [3, 3, 3], "target": [0, 0, 0], "fov": 50, "width": 8, "height": 8},
      "shapes": [{"type": "mesh", "file": "cube.stl"}]})",
                          "stl.json", scratch.path().string());
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(e.message().find(".obj, .ply, .gltf or .glb"), std::string::npos) << e.message();
  }
}

}  // namespace
}  // namespace candela
