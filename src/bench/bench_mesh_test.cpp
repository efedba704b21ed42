// The bench meshes of shared/BENCH-RAYS.md: generator counts and corner order, the OBJ reader's
// fans, index forms, relative indices and skipped faces.
#include "bench/bench_mesh.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <string>

#include "bench/bench_runner.h"
#include "bench/ray_sets.h"
#include "math/constants.h"
#include "util/error.h"

namespace candela {
namespace {

using Tri = std::array<uint32_t, 3>;

TEST(BenchMesh, SphereTriangleCounts) {
  // 4S(S-1) with S = max(2, round(sqrt(N/4))): S = 50, 158, 500.
  EXPECT_EQ(bench_sphere(10'000).mesh->triangles.size(), 9'800u);
  EXPECT_EQ(bench_sphere(100'000).mesh->triangles.size(), 99'224u);
  EXPECT_EQ(bench_sphere(1'000'000).mesh->triangles.size(), 998'000u);
  EXPECT_EQ(bench_sphere(1).mesh->triangles.size(), 8u);  // S = 2: two fans of L = 4
}

TEST(BenchMesh, SphereLayout) {
  const BenchMesh sphere = bench_sphere(10'000);  // S = 50, L = 100
  const TriangleMesh& mesh = *sphere.mesh;
  ASSERT_EQ(mesh.positions.size(), 2u + 49u * 100u);
  EXPECT_EQ(mesh.positions[0], (Vec3{0, 1, 0}));
  EXPECT_EQ(mesh.positions[1], (Vec3{0, -1, 0}));
  // r(i, j) = 2 + (i-1)L + j: the north fan (0, r(1,j+1), r(1,j)), wrapping j mod L.
  EXPECT_EQ(mesh.triangles[0], (Tri{0, 3, 2}));
  EXPECT_EQ(mesh.triangles[99], (Tri{0, 2, 101}));
  // Then the first quad of ring 1: a = r(1,0) = 2, b = 3, c = r(2,1) = 103, d = 102.
  EXPECT_EQ(mesh.triangles[100], (Tri{2, 3, 103}));
  EXPECT_EQ(mesh.triangles[101], (Tri{2, 103, 102}));
  // And the south fan last: (1, r(S-1, L-1), r(S-1, 0)).
  const uint32_t last_ring = 2 + 48 * 100;
  EXPECT_EQ(mesh.triangles.back(), (Tri{1, last_ring + 99, last_ring}));
  // Vertex r(1, 0): θ = π/50, φ = 0, rounded to float32.
  const double theta = kPi / 50;
  EXPECT_EQ(mesh.positions[2],
            (Vec3{round_to_float32(std::sin(theta)), round_to_float32(std::cos(theta)), 0.0}));
  EXPECT_NE(mesh.positions[2].x, std::sin(theta));  // really rounded
  for (const Vec3& p : mesh.positions) EXPECT_NEAR(length(p), 1.0, 1e-6);
  EXPECT_EQ(sphere.bounds.upper.y, 1.0);
  EXPECT_EQ(sphere.name, "sphere 10000");
}

TEST(BenchMesh, TerrainCountsAndCorners) {
  EXPECT_EQ(bench_terrain(20'000).mesh->triangles.size(), 20'000u);  // G = 100
  EXPECT_EQ(bench_terrain(1).mesh->triangles.size(), 2u);            // G = max(1, round(0.707)) = 1
  const BenchMesh terrain = bench_terrain(8);                        // G = 2
  const TriangleMesh& mesh = *terrain.mesh;
  ASSERT_EQ(mesh.positions.size(), 9u);
  // Quad (0,0): a = 0, b = 1, c = G+2 = 4, d = G+1 = 3 -> (a,c,b), (a,d,c).
  EXPECT_EQ(mesh.triangles[0], (Tri{0, 4, 1}));
  EXPECT_EQ(mesh.triangles[1], (Tri{0, 3, 4}));
  EXPECT_EQ(mesh.triangles[2], (Tri{1, 5, 2}));  // quad (0,1)
  // Vertex (i=0, j=1): x = 0, z = -1.
  const double y = 0.15 * std::sin(0.5) * std::cos(-2.0) + 0.05 * std::sin(1.0) * std::cos(-13.0 + 2.0) +
                   0.02 * std::sin(0.0) * std::sin(-41.0);
  EXPECT_EQ(mesh.positions[1], (Vec3{0.0, round_to_float32(y), -1.0}));
}

TEST(BenchMesh, FanTriangulationInFileOrder) {
  const BenchMesh bench = parse_bench_obj(
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0.5 1.5 0\n"
      "f 1 2 3\n"
      "f 1 2 3 4 5\n",
      "fan.obj");
  const auto& triangles = bench.mesh->triangles;
  ASSERT_EQ(triangles.size(), 4u);
  EXPECT_EQ(triangles[0], (Tri{0, 1, 2}));
  EXPECT_EQ(triangles[1], (Tri{0, 1, 2}));  // the pentagon's fan: (v0, vk, vk+1)
  EXPECT_EQ(triangles[2], (Tri{0, 2, 3}));
  EXPECT_EQ(triangles[3], (Tri{0, 3, 4}));
  EXPECT_EQ(bench.skipped_faces, 0u);
}

TEST(BenchMesh, IndexFormsAndRelativeIndices) {
  const BenchMesh bench = parse_bench_obj(
      "v 0 0 0\nv 1 0 0\nv 0 1 0\n"
      "vt 0 0\nvn 0 0 1\n"
      "f 1/1 2/1 3/1\n"
      "f 1//1 2//1 3//1\n"
      "f 1/1/1 2/1/1 3/1/1\n"
      "f -3 -2 -1\n"
      "v 1 1 0\n"
      "f -1 -2/1 -3//1\n",  // relative to the four vertices read so far
      "forms.obj");
  const auto& triangles = bench.mesh->triangles;
  ASSERT_EQ(triangles.size(), 5u);
  for (int k = 0; k < 4; ++k) EXPECT_EQ(triangles[k], (Tri{0, 1, 2}));
  EXPECT_EQ(triangles[4], (Tri{3, 2, 1}));
}

TEST(BenchMesh, SkipsOutOfRangeFacesAndIgnoresOtherLines) {
  const BenchMesh bench = parse_bench_obj(
      "# comment\no thing\ng group\nusemtl red\nmtllib x.mtl\ns 1\n"
      "v 0 0 0\nv 1 0 0\nv 0 1 0\n"
      "f 1 2 5\n"   // out of range
      "f 0 1 2\n"   // 0 is never valid
      "f -4 1 2\n"  // before the first vertex
      "f 1 2\n"     // not a polygon
      "f 3 2 1\n"
      "v 0 0 5\n",  // an unused vertex still counts in the bounds
      "skip.obj");
  ASSERT_EQ(bench.mesh->triangles.size(), 1u);
  EXPECT_EQ(bench.mesh->triangles[0], (Tri{2, 1, 0}));
  EXPECT_EQ(bench.skipped_faces, 4u);
  EXPECT_EQ(bench.bounds.upper.z, 5.0);
  EXPECT_EQ(bench.mesh->positions.size(), 4u);
}

TEST(BenchMesh, ForwardIndicesResolveAgainstTheWholeFile) {
  const BenchMesh bench = parse_bench_obj("f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n", "forward.obj");
  ASSERT_EQ(bench.mesh->triangles.size(), 1u);
  EXPECT_EQ(bench.skipped_faces, 0u);
}

TEST(BenchMesh, CoordinatesAreFloat32) {
  const BenchMesh bench = parse_bench_obj("v 0.1 -0.2 +3e-1\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "float.obj");
  EXPECT_EQ(bench.mesh->positions[0], (Vec3{0.1f, -0.2f, 0.3f}));
}

TEST(BenchMesh, BadInputIsAnInputErrorWithTheLine) {
  try {
    parse_bench_obj("v 0 0 0\nv 1 zero 0\n", "bad.obj");
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.location().line, 2);
    EXPECT_EQ(e.location().file, "bad.obj");
  }
  EXPECT_THROW(parse_bench_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 x 3\n", "bad.obj"), InputError);
  EXPECT_THROW(parse_bench_obj("v 0 0 nan\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "bad.obj"), InputError);
  EXPECT_THROW(parse_bench_obj("v 0 0 0\n", "empty.obj"), InputError);
  EXPECT_THROW(read_bench_obj("/nonexistent/mesh.obj"), InputError);
}

// A face of more corners than the limit is refused at its line (its fan made `candela
// bench` on a 10⁵-corner disc run for a minute at 0.007 Mrays/s); the limit itself is read.
TEST(BenchMesh, AFaceOfMoreCornersThanTheLimitIsRefusedAtItsLine) {
  const auto polygon = [](std::size_t corners) {
    std::string text, face = "f";
    for (std::size_t i = 0; i < corners; ++i) {
      const double angle = 2 * kPi * static_cast<double>(i) / static_cast<double>(corners);
      text += fmt::format("v {} {} 0\n", std::cos(angle), std::sin(angle));
      face += fmt::format(" {}", i + 1);
    }
    return text + "# the face\n" + face + "\n";
  };
  EXPECT_EQ(parse_bench_obj(polygon(kMaxBenchFaceCorners), "ok.obj").mesh->triangles.size(),
            kMaxBenchFaceCorners - 2);
  try {
    parse_bench_obj(polygon(kMaxBenchFaceCorners + 1), "disc.obj");
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.location().file, "disc.obj");
    EXPECT_EQ(e.location().line, static_cast<int>(kMaxBenchFaceCorners) + 3);
    EXPECT_NE(std::string(e.what()).find("a face of 1001 corners"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("at most 1000 corners"), std::string::npos) << e.what();
  }
}

TEST(BenchMesh, DegenerateTrianglesKeepTheirIds) {
  const BenchMesh bench =
      parse_bench_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\nf 1 2 4\nf 1 2 3\n", "degenerate.obj");
  const BenchScene scene(bench.mesh);
  ASSERT_EQ(scene.primitives().size(), 1u);  // the collinear triangle is never hit
  EXPECT_EQ(scene.skipped_degenerate(), 1u);
  EXPECT_EQ(scene.triangle_id(0), 1u);
}

// 20,000 copies of one face made `candela bench` on a 180 KB file run for most of an
// hour (0.003 Mrays/s); the copies are merged into the first, which keeps its id.
TEST(BenchMesh, DuplicateTrianglesAreMergedAndKeepTheFirstId) {
  std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  for (int i = 0; i < 20000; ++i) obj += "f 1 2 3\n";
  const BenchMesh bench = parse_bench_obj(obj, "copies.obj");
  EXPECT_EQ(bench.mesh->triangles.size(), 20000u);  // the ids of BENCH-RAYS.md
  const BenchScene scene(bench.mesh);
  ASSERT_EQ(scene.primitives().size(), 1u);
  EXPECT_EQ(scene.triangle_id(0), 0u);
  EXPECT_EQ(scene.merged_duplicates(), 19999u);
}

}  // namespace
}  // namespace candela
