#include "scene/gltf_import.h"

#include <gtest/gtest.h>

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
#include "scene/scene.h"
#include "scene/scene_loader.h"

namespace candela {
namespace {

const SourceLocation kFrom{"scene.json", 3, 7, "shapes[0].file"};

using testing::write_file;

std::string base64(const std::string& bytes) {
  static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  std::size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const unsigned v = (static_cast<unsigned char>(bytes[i]) << 16) | (static_cast<unsigned char>(bytes[i + 1]) << 8) |
                       static_cast<unsigned char>(bytes[i + 2]);
    out += {table[(v >> 18) & 63], table[(v >> 12) & 63], table[(v >> 6) & 63], table[v & 63]};
  }
  if (i + 1 == bytes.size()) {
    const unsigned v = static_cast<unsigned char>(bytes[i]) << 16;
    out += {table[(v >> 18) & 63], table[(v >> 12) & 63], '=', '='};
  } else if (i + 2 == bytes.size()) {
    const unsigned v = (static_cast<unsigned char>(bytes[i]) << 16) | (static_cast<unsigned char>(bytes[i + 1]) << 8);
    out += {table[(v >> 18) & 63], table[(v >> 12) & 63], table[(v >> 6) & 63], '='};
  }
  return out;
}

template <typename T>
void put(std::string& bytes, T value) {
  char raw[sizeof(T)];
  std::memcpy(raw, &value, sizeof(T));
  bytes.append(raw, sizeof(T));
}

// A unit square in z = 0 (4 float positions, 48 bytes) and two triangles of uint16 indices (12).
std::string square_buffer(float nan_at_y = 0, std::uint16_t last_index = 3) {
  std::string bytes;
  const float corners[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (int v = 0; v < 4; ++v) {
    put<float>(bytes, corners[v][0]);
    put<float>(bytes, v == 1 ? nan_at_y : corners[v][1]);
    put<float>(bytes, 0);
  }
  for (std::uint16_t i : {0, 1, 2, 0, 2}) put<std::uint16_t>(bytes, i);
  put<std::uint16_t>(bytes, last_index);
  return bytes;
}

// The JSON around a buffer of square_buffer's layout; uri empty for .glb's BIN chunk.
std::string square_json(const std::string& uri, const std::string& node = R"({"mesh": 0})",
                        const std::string& extra_primitive = "") {
  return R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
    "nodes": [)" + node + R"(],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "mode": 4})" + extra_primitive + R"(]}],
    "buffers": [{"byteLength": 60)" + (uri.empty() ? std::string() : R"(, "uri": ")" + uri + "\"") + R"(}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48},
                    {"buffer": 0, "byteOffset": 48, "byteLength": 12}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
                   "min": [0, 0, 0], "max": [1, 1, 0]},
                  {"bufferView": 1, "componentType": 5123, "count": 6, "type": "SCALAR"}]})";
}

std::string data_uri(const std::string& bytes) { return "data:application/octet-stream;base64," + base64(bytes); }

std::string glb(const std::string& json, const std::string& bin) {
  std::string j = json;
  while (j.size() % 4 != 0) j += ' ';
  std::string b = bin;
  while (b.size() % 4 != 0) b += '\0';
  std::string out = "glTF";
  put<std::uint32_t>(out, 2);
  put<std::uint32_t>(out, static_cast<std::uint32_t>(12 + 8 + j.size() + 8 + b.size()));
  put<std::uint32_t>(out, static_cast<std::uint32_t>(j.size()));
  out += "JSON" + j;
  put<std::uint32_t>(out, static_cast<std::uint32_t>(b.size()));
  out += std::string("BIN\0", 4) + b;
  return out;
}

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
      write_file(scratch.path() / "square.gltf",
            square_json("square.bin", R"({"children": [1], "translation": [0, 0, 5]}, {"mesh": 0, "scale": [2, 2, 2]})")),
      kFrom);
  ASSERT_TRUE(result.mesh);
  const Bounds3 bounds = result.mesh->bounds();
  EXPECT_DOUBLE_EQ(bounds.upper.x, 2.0);
  EXPECT_DOUBLE_EQ(bounds.upper.y, 2.0);
  EXPECT_DOUBLE_EQ(bounds.lower.z, 5.0);
  EXPECT_DOUBLE_EQ(bounds.upper.z, 5.0);
}

TEST(GltfImport, BinaryGlb) {
  testing::ScratchDirectory scratch("gltf");
  const auto result = import_gltf(write_file(scratch.path() / "square.glb", glb(square_json(""), square_buffer())), kFrom);
  ASSERT_TRUE(result.mesh);
  EXPECT_EQ(result.mesh->triangles.size(), 2u);
}

TEST(GltfImport, OtherPrimitiveModesAreSkippedWithAWarning) {
  testing::ScratchDirectory scratch("gltf");
  const auto result =
      import_gltf(write_file(scratch.path() / "points.gltf",
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
      write_file(scratch.path() / "nan.gltf", square_json(data_uri(square_buffer(std::numeric_limits<float>::quiet_NaN()))));
  std::string message = error_of(nan);
  EXPECT_NE(message.find(nan), std::string::npos) << message;
  EXPECT_NE(message.find("vertex 1 has a non-finite position"), std::string::npos) << message;

  const std::string index = write_file(scratch.path() / "index.gltf", square_json(data_uri(square_buffer(0, 9))));
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

TEST(GltfImport, LoadedSceneHasTheTriangles) {
  testing::ScratchDirectory scratch("gltf");
  write_file(scratch.path() / "square.glb", glb(square_json(""), square_buffer()));
  const auto scene = read_scene_text(R"({"format": "candela/1",
    "camera": {"eye": [0.5, 0.5, 3], "target": [0.5, 0.5, 0], "fov": 50, "width": 8, "height": 8},
    "shapes": [{"type": "mesh", "file": "square.glb", "material": {"kd": 0.5}}]})",
                                     "gltf.json", scratch.path().string(), {}, {});
  EXPECT_EQ(scene->primitives.size(), 2u);
  EXPECT_DOUBLE_EQ(scene->bounds().upper.x, 1.0);
  EXPECT_DOUBLE_EQ(scene->bounds().upper.y, 1.0);
}

}  // namespace
}  // namespace candela
