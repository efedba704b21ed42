#include "io/ply_import.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "../../tests/scratch_directory.h"
#include "geometry/triangle_mesh.h"
#include "io/mesh_test_files.h"

namespace candela {
namespace {

const SourceLocation kFrom{"scene.json", 3, 7, "shapes[0].file"};

using testing::kAsciiCube;
using testing::write_file;

std::string ply_error(const std::string& path) {
  try {
    (void)import_ply(path, kFrom);
  } catch (const InputError& e) {
    EXPECT_EQ(e.location().json_path, "shapes[0].file");
    return e.message();
  }
  ADD_FAILURE() << "no error for " << path;
  return "";
}

TEST(PlyImport, AsciiCubeQuadsBecomeTwoTrianglesEach) {
  testing::ScratchDirectory scratch("ply");
  const auto result = import_ply(write_file(scratch.path() / "cube.ply", kAsciiCube), kFrom);
  ASSERT_TRUE(result.mesh);
  EXPECT_EQ(result.mesh->positions.size(), 8u);
  EXPECT_EQ(result.mesh->triangles.size(), 12u);
  EXPECT_EQ(result.triangle_material, std::vector<int>(12, -1));
  EXPECT_TRUE(result.mesh->corner_normals.empty());
  EXPECT_TRUE(result.mesh->corner_uvs.empty());
  EXPECT_TRUE(result.materials.empty());
  const Vec3 centre{0.5, 0.5, 0.5};
  for (std::size_t t = 0; t < 12; ++t)
    EXPECT_GT(dot(result.mesh->face_cross(t), result.mesh->triangle_bounds(t).center() - centre), 0) << t;
  EXPECT_NO_THROW(result.mesh->validate());
}

// Two triangles (a quad split) with normals and uvs; an extra list property in each face and
// an extra element holding a list, to be skipped by size.
struct Builder {
  bool big = false;
  std::string bytes;
  template <typename T>
  void put(T value) {
    char raw[sizeof(T)];
    std::memcpy(raw, &value, sizeof(T));
    if (big) std::reverse(raw, raw + sizeof(T));
    bytes.append(raw, sizeof(T));
  }
};

std::string binary_quad(bool big) {
  Builder b{big, std::string("ply\nformat ") + (big ? "binary_big_endian" : "binary_little_endian") +
                     " 1.0\n"
                     "element vertex 4\nproperty double x\nproperty float y\nproperty float z\n"
                     "property float nx\nproperty float ny\nproperty float nz\n"
                     "property float s\nproperty float t\nproperty int16 extra\n"
                     "element material 2\nproperty list uint8 float32 values\n"
                     "element face 1\nproperty list uint8 uint32 vertex_indices\n"
                     "property list ushort short tags\nend_header\n"};
  const float corners[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (const auto& c : corners) {
    b.put<double>(c[0]);
    b.put<float>(c[1]);
    b.put<float>(0);
    b.put<float>(0);
    b.put<float>(0);
    b.put<float>(2);  // normals normalised on import
    b.put<float>(c[0]);
    b.put<float>(c[1]);
    b.put<std::int16_t>(-5);
  }
  b.put<std::uint8_t>(3);
  for (int k = 0; k < 3; ++k) b.put<float>(0.5f);
  b.put<std::uint8_t>(0);
  b.put<std::uint8_t>(4);
  for (std::uint32_t i : {0u, 1u, 2u, 3u}) b.put<std::uint32_t>(i);
  b.put<std::uint16_t>(2);
  b.put<std::int16_t>(7);
  b.put<std::int16_t>(8);
  return b.bytes;
}

void expect_quad(const ObjImport& result) {
  ASSERT_TRUE(result.mesh);
  const TriangleMesh& mesh = *result.mesh;
  ASSERT_EQ(mesh.positions.size(), 4u);
  ASSERT_EQ(mesh.triangles.size(), 2u);
  EXPECT_EQ(mesh.positions[2].x, 1);
  EXPECT_EQ(mesh.positions[2].y, 1);
  EXPECT_EQ(mesh.triangles[1][0], 0u);
  EXPECT_EQ(mesh.triangles[1][1], 2u);
  EXPECT_EQ(mesh.triangles[1][2], 3u);
  ASSERT_EQ(mesh.corner_normals.size(), 2u);
  EXPECT_DOUBLE_EQ(mesh.corner_normals[0][1].z, 1.0);
  ASSERT_EQ(mesh.corner_uvs.size(), 2u);
  EXPECT_DOUBLE_EQ(mesh.corner_uvs[1][1].x, 1.0);
  EXPECT_DOUBLE_EQ(mesh.corner_uvs[1][2].y, 1.0);
  EXPECT_NO_THROW(mesh.validate());
}

TEST(PlyImport, BinaryLittleEndianWithNormalsAndUvs) {
  testing::ScratchDirectory scratch("ply");
  expect_quad(import_ply(write_file(scratch.path() / "le.ply", binary_quad(false)), kFrom));
}

TEST(PlyImport, BinaryBigEndianWithNormalsAndUvs) {
  testing::ScratchDirectory scratch("ply");
  expect_quad(import_ply(write_file(scratch.path() / "be.ply", binary_quad(true)), kFrom));
}

TEST(PlyImport, TruncatedBinaryGivesTheFileAndByteOffset) {
  testing::ScratchDirectory scratch("ply");
  const std::string whole = binary_quad(false);
  const std::string path = write_file(scratch.path() / "cut.ply", whole.substr(0, whole.size() - 3));
  const std::string message = ply_error(path);
  EXPECT_NE(message.find(path), std::string::npos) << message;
  EXPECT_NE(message.find("byte"), std::string::npos) << message;
}

TEST(PlyImport, HugeCountsAreRefusedBeforeAllocating) {
  testing::ScratchDirectory scratch("ply");
  const std::string path =
      write_file(scratch.path() / "huge.ply",
                 "ply\nformat binary_little_endian 1.0\nelement vertex 1000000000\n"
                 "property float x\nproperty float y\nproperty float z\nend_header\n0000");
  const std::string message = ply_error(path);
  EXPECT_NE(message.find("1000000000"), std::string::npos) << message;
  const std::string ascii =
      write_file(scratch.path() / "huge-ascii.ply",
                 "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                 "property float z\nelement face 18446744073709551615\n"
                 "property list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n");
  EXPECT_NE(ply_error(ascii).find("face"), std::string::npos);
  const std::string list =
      write_file(scratch.path() / "huge-list.ply",
                 "ply\nformat binary_little_endian 1.0\nelement vertex 0\nproperty float x\n"
                 "property float y\nproperty float z\nelement face 1\n"
                 "property list uint int vertex_indices\nend_header\n\xff\xff\xff\x7f");
  EXPECT_NE(ply_error(list).find("runs past the end"), std::string::npos);
}

TEST(PlyImport, BadIndexGivesTheLine) {
  testing::ScratchDirectory scratch("ply");
  const std::string path =
      write_file(scratch.path() / "bad.ply",
                 "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                 "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                 "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n");
  const std::string message = ply_error(path);
  EXPECT_NE(message.find(path), std::string::npos) << message;
  EXPECT_NE(message.find("line 13"), std::string::npos) << message;
  EXPECT_NE(message.find("vertex 3"), std::string::npos) << message;
}

// A large face is triangulated as an OBJ face is (geometry/face_triangulation.h): a
// convex one halved (not fanned: every triangle's box would reach corner 0), a non-convex one of
// more than kMaxNonConvexFaceCorners corners refused with the face's number and line.
TEST(PlyImport, LargeFacesAreTriangulatedAsObjFacesAndRefusedPastTheLimit) {
  testing::ScratchDirectory scratch("ply");
  const auto polygon = [&](const std::string& name, std::size_t corners, bool star) {
    std::string text = "ply\nformat ascii 1.0\nelement vertex " + std::to_string(corners) +
                       "\nproperty float x\nproperty float y\nproperty float z\nelement face 1\n"
                       "property list uint int vertex_indices\nend_header\n";
    std::string face = std::to_string(corners);
    for (std::size_t i = 0; i < corners; ++i) {
      const double angle = 2 * 3.14159265358979 * static_cast<double>(i) / static_cast<double>(corners);
      const double radius = star && i % 2 ? 0.5 : 1.0;
      text +=
          std::to_string(radius * std::cos(angle)) + " " + std::to_string(radius * std::sin(angle)) + " 0\n";
      face += " " + std::to_string(i);
    }
    return write_file(scratch.path() / name, text + face + "\n");
  };
  const ObjImport disc = import_ply(polygon("disc.ply", 5000, false), kFrom);
  ASSERT_EQ(disc.mesh->triangles.size(), 4998u);
  std::size_t at_corner_zero = 0;
  for (const auto& t : disc.mesh->triangles) at_corner_zero += std::count(t.begin(), t.end(), 0u);
  EXPECT_LE(at_corner_zero, 40u);  // a fan: all 4998
  EXPECT_EQ(import_ply(polygon("star.ply", 1000, true), kFrom).mesh->triangles.size(), 998u);
  const std::string message = ply_error(polygon("big-star.ply", 1002, true));
  EXPECT_NE(message.find("line 1012"), std::string::npos) << message;
  EXPECT_NE(message.find("face 0: a face of 1002 corners that is not convex"), std::string::npos) << message;
}

TEST(PlyImport, NonFiniteCoordinateNamesTheVertex) {
  testing::ScratchDirectory scratch("ply");
  const std::string path =
      write_file(scratch.path() / "nan.ply",
                 "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                 "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                 "end_header\n0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n");
  const std::string message = ply_error(path);
  EXPECT_NE(message.find("vertex 1 has a non-finite coordinate"), std::string::npos) << message;
  EXPECT_NE(message.find("line 11"), std::string::npos) << message;
}

TEST(PlyImport, MalformedHeadersAndMissingFiles) {
  testing::ScratchDirectory scratch("ply");
  EXPECT_NE(ply_error((scratch.path() / "none.ply").string()).find("not found"), std::string::npos);
  EXPECT_NE(ply_error(write_file(scratch.path() / "a.ply", "plx\n")).find("'ply'"), std::string::npos);
  EXPECT_NE(ply_error(write_file(scratch.path() / "b.ply", "ply\nformat ascii 1.0\nelement vertex 1\n"))
                .find("end_header"),
            std::string::npos);
  EXPECT_NE(
      ply_error(write_file(scratch.path() / "c.ply", "ply\nformat ascii 1.0\nproperty float x\nend_header\n"))
          .find("line 3"),
      std::string::npos);
  EXPECT_NE(
      ply_error(write_file(scratch.path() / "d.ply",
                           "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
                           "property float z\nend_header\n0 0 0\n"))
          .find("no triangles"),
      std::string::npos);
}

}  // namespace
}  // namespace candela
