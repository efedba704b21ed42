#include "io/gltf_import.h"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "../../tests/scratch_directory.h"
#include "geometry/triangle_mesh.h"
#include "io/mesh_test_files.h"

namespace candela {
namespace {

const SourceLocation kFrom{"scene.json", 3, 7, "shapes[0].file"};

using testing::data_uri;
using testing::glb;
using testing::square_buffer;
using testing::square_json;
using testing::write_file;

std::string error_of(const std::string& path) {
  try {
    (void)import_gltf(path, kFrom);
  } catch (const InputError& e) {
    EXPECT_EQ(e.location().json_path, "shapes[0].file");
    return e.message();
  }
  ADD_FAILURE() << "no error for " << path;
  return "";
}

TEST(GltfImport, EmbeddedBufferWithUint16Indices) {
  testing::ScratchDirectory scratch("gltf");
  const auto result =
      import_gltf(write_file(scratch.path() / "square.gltf", square_json(data_uri(square_buffer()))), kFrom);
  ASSERT_TRUE(result.mesh);
  EXPECT_EQ(result.mesh->positions.size(), 4u);
  ASSERT_EQ(result.mesh->triangles.size(), 2u);
  EXPECT_EQ(result.mesh->triangles[1][2], 3u);
  EXPECT_EQ(result.triangle_material, std::vector<int>(2, -1));
  EXPECT_GT(result.mesh->face_cross(0).z, 0);
  EXPECT_TRUE(result.warnings.empty());
}

TEST(GltfImport, ExternalBufferAndNodeTransform) {
  testing::ScratchDirectory scratch("gltf");
  write_file(scratch.path() / "square.bin", square_buffer());
  const auto result = import_gltf(
      write_file(
          scratch.path() / "square.gltf",
          square_json("square.bin",
                      R"({"children": [1], "translation": [0, 0, 5]}, {"mesh": 0, "scale": [2, 2, 2]})")),
      kFrom);
  ASSERT_TRUE(result.mesh);
  const Bounds3 bounds = result.mesh->bounds();
  EXPECT_DOUBLE_EQ(bounds.upper.x, 2.0);
  EXPECT_DOUBLE_EQ(bounds.upper.y, 2.0);
  EXPECT_DOUBLE_EQ(bounds.lower.z, 5.0);
  EXPECT_DOUBLE_EQ(bounds.upper.z, 5.0);
}

// Issue 21: an external buffer that is a FIFO blocked in open() forever, /dev/zero was read until
// memory ran out; both are refused, naming the buffer and what it is. (A hang here would hang the
// test: the check is made before any open.)
TEST(GltfImport, ANonRegularExternalBufferIsRefused) {
  testing::ScratchDirectory scratch("gltf");
  const std::filesystem::path pipe = scratch.path() / "pipe.bin";
  ASSERT_EQ(::mkfifo(pipe.c_str(), 0600), 0);
  const std::string fifo_error = error_of(write_file(scratch.path() / "fifo.gltf", square_json("pipe.bin")));
  EXPECT_NE(fifo_error.find("is a FIFO (named pipe), not a regular file"), std::string::npos) << fifo_error;
  EXPECT_NE(fifo_error.find("pipe.bin"), std::string::npos) << fifo_error;
  std::filesystem::create_symlink("/dev/zero", scratch.path() / "zero.bin");
  const std::string device_error =
      error_of(write_file(scratch.path() / "zero.gltf", square_json("zero.bin")));
  EXPECT_NE(device_error.find("is a device, not a regular file"), std::string::npos) << device_error;
}

TEST(GltfImport, BinaryGlb) {
  testing::ScratchDirectory scratch("gltf");
  const auto result =
      import_gltf(write_file(scratch.path() / "square.glb", glb(square_json(""), square_buffer())), kFrom);
  ASSERT_TRUE(result.mesh);
  EXPECT_EQ(result.mesh->triangles.size(), 2u);
}

TEST(GltfImport, OtherPrimitiveModesAreSkippedWithAWarning) {
  testing::ScratchDirectory scratch("gltf");
  const auto result = import_gltf(write_file(scratch.path() / "points.gltf",
                                             square_json(data_uri(square_buffer()), R"({"mesh": 0})",
                                                         R"(, {"attributes": {"POSITION": 0}, "mode": 0})")),
                                  kFrom);
  EXPECT_EQ(result.mesh->triangles.size(), 2u);
  ASSERT_EQ(result.warnings.size(), 1u);
  EXPECT_NE(result.warnings[0].find("mesh 0 primitive 1"), std::string::npos) << result.warnings[0];
}

TEST(GltfImport, BadInputsAreRefusedNamingTheFile) {
  testing::ScratchDirectory scratch("gltf");
  const std::string nan =
      write_file(scratch.path() / "nan.gltf",
                 square_json(data_uri(square_buffer(std::numeric_limits<float>::quiet_NaN()))));
  std::string message = error_of(nan);
  EXPECT_NE(message.find(nan), std::string::npos) << message;
  EXPECT_NE(message.find("vertex 1 has a non-finite position"), std::string::npos) << message;

  const std::string index =
      write_file(scratch.path() / "index.gltf", square_json(data_uri(square_buffer(0, 9))));
  message = error_of(index);
  EXPECT_NE(message.find("refers to vertex 9"), std::string::npos) << message;

  const std::string broken = write_file(scratch.path() / "broken.gltf", "{\"asset\": ");
  message = error_of(broken);
  EXPECT_NE(message.find(broken), std::string::npos) << message;

  const std::string short_glb = glb(square_json(""), square_buffer());
  const std::string cut = write_file(scratch.path() / "cut.glb", short_glb.substr(0, short_glb.size() - 20));
  message = error_of(cut);
  EXPECT_NE(message.find(cut), std::string::npos) << message;

  EXPECT_NE(error_of((scratch.path() / "none.glb").string()).find("not found"), std::string::npos);
}

}  // namespace
}  // namespace candela
