// Mesh files (src/io/*_import.cpp) loaded through a scene's "mesh" shape (src/scene/): the
// importers' results placed in the scene, and the extensions the shape accepts.
#include <gtest/gtest.h>

#include <chrono>
#include <string>

#include "integrators/scene_loading.h"
#include "io/mesh_test_files.h"
#include "render_support.h"
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

// An OBJ face repeated tens of thousands of times became as many coincident
// triangles, and every ray that met them tested them all to keep the lowest index among equal
// distances (render at 32×24 on 10⁶ copies: 10–20 s). Copies are merged at load, with a warning
// that counts them; the reversed winding faces the other way and stays.
TEST(ObjImport, DuplicateTrianglesAreMergedAtLoadWithAWarning) {
  testing::ScratchDirectory scratch("duplicates");
  std::string obj = "v -1 -1 0\nv 1 -1 0\nv 0 1 0\nv -1 -1 0\n";
  for (int i = 0; i < 20000; ++i) obj += i % 2 ? "f 1 2 3\n" : "f 2 3 4\n";  // rotated, other vertex
  obj += "f 3 2 1\n";
  write_file(scratch.path() / "copies.obj", obj);
  const auto start = std::chrono::steady_clock::now();
  const auto scene = load_scene_text(R"({"format": "candela/1",
    "camera": {"eye": [0, 0, 3], "target": [0, 0, 0], "fov": 50, "width": 32, "height": 24},
    "lights": [{"type": "point", "position": [0, 0, 2], "intensity": 5}],
    "shapes": [{"type": "mesh", "file": "copies.obj", "material": {"kd": 0.5}}]})",
                                     "copies.json", scratch.path().string());
  EXPECT_EQ(scene->primitives.size(), 2u);
  bool warned = false;
  for (const std::string& warning : scene->warnings)
    warned = warned || warning.find("merged 19999 duplicate triangle(s)") != std::string::npos;
  EXPECT_TRUE(warned);
  const Film film = testing::render_scene(*scene, "whitted");
  EXPECT_GT(film.at(16, 12).r, 0.0);  // the triangle is there
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 10.0);
}

}  // namespace
}  // namespace candela
