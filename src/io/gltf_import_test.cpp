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

std::string gltf_error(const std::string& path) {
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

// An external buffer that is a FIFO blocked in open() forever, /dev/zero was read until
// memory ran out; both are refused, naming the buffer and what it is. (A hang here would hang the
// test: the check is made before any open.)
TEST(GltfImport, ANonRegularExternalBufferIsRefused) {
  testing::ScratchDirectory scratch("gltf");
  const std::filesystem::path pipe = scratch.path() / "pipe.bin";
  ASSERT_EQ(::mkfifo(pipe.c_str(), 0600), 0);
  const std::string fifo_error =
      gltf_error(write_file(scratch.path() / "fifo.gltf", square_json("pipe.bin")));
  EXPECT_NE(fifo_error.find("is a FIFO (named pipe), not a regular file"), std::string::npos) << fifo_error;
  EXPECT_NE(fifo_error.find("pipe.bin"), std::string::npos) << fifo_error;
  std::filesystem::create_symlink("/dev/zero", scratch.path() / "zero.bin");
  const std::string device_error =
      gltf_error(write_file(scratch.path() / "zero.gltf", square_json("zero.bin")));
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
  std::string message = gltf_error(nan);
  EXPECT_NE(message.find(nan), std::string::npos) << message;
  EXPECT_NE(message.find("vertex 1 has a non-finite position"), std::string::npos) << message;

  const std::string index =
      write_file(scratch.path() / "index.gltf", square_json(data_uri(square_buffer(0, 9))));
  message = gltf_error(index);
  EXPECT_NE(message.find("refers to vertex 9"), std::string::npos) << message;

  const std::string broken = write_file(scratch.path() / "broken.gltf", "{\"asset\": ");
  message = gltf_error(broken);
  EXPECT_NE(message.find(broken), std::string::npos) << message;

  const std::string short_glb = glb(square_json(""), square_buffer());
  const std::string cut = write_file(scratch.path() / "cut.glb", short_glb.substr(0, short_glb.size() - 20));
  message = gltf_error(cut);
  EXPECT_NE(message.find(cut), std::string::npos) << message;

  EXPECT_NE(gltf_error((scratch.path() / "none.glb").string()).find("not found"), std::string::npos);
}

// square_json with `from` replaced by `to` (which must occur once).
std::string edited_square(const std::string& from, const std::string& to,
                          const std::string& node = R"({"mesh": 0})") {
  std::string json = square_json(data_uri(square_buffer()), node);
  const std::size_t at = json.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) json.replace(at, from.size(), to);
  return json;
}

// tinygltf reads an optional byteOffset or byteStride that is not a non-negative
// integer as 0 without a word (an accessor at byteOffset -4 read its buffer from the start), and
// sizes past the end were refused only as "lies outside its buffer". Each is now refused by its
// JSON path, with the numbers that do not fit.
TEST(GltfImport, BadByteOffsetsLengthsAndStridesAreRefusedByTheirJsonPath) {
  testing::ScratchDirectory scratch("gltf");
  const auto expect_error = [&](const std::string& name, const std::string& json, const std::string& what) {
    const std::string path = write_file(scratch.path() / name, json);
    const std::string message = gltf_error(path);
    EXPECT_NE(message.find(path), std::string::npos) << message;
    EXPECT_NE(message.find(what), std::string::npos) << message;
  };
  const std::string accessor0 = R"("bufferView": 0, "componentType": 5126)";
  expect_error("negative-accessor-offset.gltf",
               edited_square(accessor0, R"("bufferView": 0, "byteOffset": -4, "componentType": 5126)"),
               "accessors[0].byteOffset: must be a non-negative integer (found -4)");
  expect_error("fraction.gltf",
               edited_square(accessor0, R"("bufferView": 0, "byteOffset": 1.5, "componentType": 5126)"),
               "accessors[0].byteOffset: must be a non-negative integer (found 1.5)");
  expect_error("negative-view-offset.gltf", edited_square(R"("byteOffset": 48)", R"("byteOffset": -48)"),
               "bufferViews[1].byteOffset: must be a non-negative integer (found -48)");
  expect_error("huge-view-offset.gltf", edited_square(R"("byteOffset": 0,)", R"("byteOffset": 1e30,)"),
               "bufferViews[0].byteOffset: must be a non-negative integer (found 1e+30)");
  const std::string view0 = R"("byteOffset": 0, "byteLength": 48})";
  expect_error("negative-stride.gltf",
               edited_square(view0, R"("byteOffset": 0, "byteLength": 48, "byteStride": -12})"),
               "bufferViews[0].byteStride: must be a non-negative integer (found -12)");
  expect_error("short-stride.gltf",
               edited_square(view0, R"("byteOffset": 0, "byteLength": 48, "byteStride": 4})"),
               "bufferViews[0].byteStride: 4 is less than the 12 bytes of an element of accessor 0");
  expect_error("overflowing-accessor-offset.gltf",
               edited_square(accessor0,
                             R"("bufferView": 0, "byteOffset": 18446744073709551615, "componentType": 5126)"),
               "accessors[0].byteOffset: 18446744073709551615 is past the end of bufferView 0 (48 bytes)");
  expect_error("overflowing-view-length.gltf",
               edited_square(view0, R"("byteOffset": 0, "byteLength": 18446744073709551615})"),
               "bufferViews[0]: byteOffset 0 + byteLength 18446744073709551615 is past the end of buffer 0 "
               "(60 bytes)");
  expect_error("count.gltf", edited_square(R"("count": 4)", R"("count": 5)"),
               "accessors[0].count: 5 elements of 12 bytes, 12 bytes apart from byteOffset 0, do not fit in "
               "bufferView 0 (48 bytes)");
  // The same check reads the JSON chunk of a .glb.
  const std::string glb_json = square_json("");
  const std::size_t at = glb_json.find(accessor0);
  ASSERT_NE(at, std::string::npos);
  const std::string negative_glb =
      glb(std::string(glb_json).replace(at, accessor0.size(),
                                        R"("bufferView": 0, "byteOffset": -4, "componentType": 5126)"),
          square_buffer());
  expect_error("negative.glb", negative_glb,
               "accessors[0].byteOffset: must be a non-negative integer (found -4)");
}

// A node matrix holding 1e300 was refused as "matrix is singular"; what is wrong is the
// size of its numbers, or of the transform composed down the node tree. A quaternion of tiny
// components (its norm underflows to 0) was left unnormalised, a near-zero matrix that rotated
// nothing; the zero quaternion is refused.
TEST(GltfImport, NodeTransformsNameTheNodeAndWhatIsWrong) {
  testing::ScratchDirectory scratch("gltf");
  const auto error_for_node = [&](const std::string& name, const std::string& nodes) {
    return gltf_error(write_file(scratch.path() / name, square_json(data_uri(square_buffer()), nodes)));
  };
  std::string message = error_for_node(
      "matrix.gltf", R"({"mesh": 0, "matrix": [1e300, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]})");
  EXPECT_NE(message.find("nodes[0].matrix[0]: magnitude above 1e16 is not supported (found 1e+300)"),
            std::string::npos)
      << message;
  EXPECT_EQ(message.find("singular"), std::string::npos) << message;
  message = error_for_node("translation.gltf", R"({"mesh": 0, "translation": [0, -1e17, 0]})");
  EXPECT_NE(message.find("nodes[0].translation[1]: magnitude above 1e16 is not supported (found -1e+17)"),
            std::string::npos)
      << message;
  message = error_for_node(
      "chain.gltf", R"({"children": [1], "scale": [1e10, 1e10, 1e10]}, {"mesh": 0, "scale": [1e10, 1, 1]})");
  EXPECT_NE(
      message.find("nodes[1]: the transform composed from the scene's root down to this node has an entry of "
                   "magnitude 1e+20, above the supported 1e16"),
      std::string::npos)
      << message;
  message = error_for_node("zero-rotation.gltf", R"({"mesh": 0, "rotation": [0, 0, 0, 0]})");
  EXPECT_NE(message.find("nodes[0].rotation: the zero quaternion"), std::string::npos) << message;
  message = error_for_node("zero-scale.gltf", R"({"mesh": 0, "scale": [1, 0, 1]})");
  EXPECT_NE(message.find("nodes[0]: transform: matrix is singular"), std::string::npos) << message;

  // 90° about z with components of 1e-200: the square [0, 1]² turns to x in [-1, 0].
  const auto result = import_gltf(
      write_file(
          scratch.path() / "tiny-rotation.gltf",
          square_json(data_uri(square_buffer()), R"({"mesh": 0, "rotation": [0, 0, 1e-200, 1e-200]})")),
      kFrom);
  const Bounds3 bounds = result.mesh->bounds();
  EXPECT_NEAR(bounds.lower.x, -1, 1e-12);
  EXPECT_NEAR(bounds.upper.x, 0, 1e-12);
  EXPECT_NEAR(bounds.upper.y, 1, 1e-12);
}

}  // namespace
}  // namespace candela
