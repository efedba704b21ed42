#include "geometry/triangle_mesh.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <memory>
#include <tuple>
#include <vector>

#include "math/constants.h"
#include "math/pcg32.h"
#include "math/transform.h"
#include "shape_test_support.h"

namespace candela {
namespace {

using candela::testing::expect_vec_near;
using candela::testing::make_ray;

// The unit right triangle in the z = 0 plane, counter-clockwise seen from +z.
std::shared_ptr<TriangleMesh> unit_triangle() {
  auto mesh = std::make_shared<TriangleMesh>();
  mesh->positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  mesh->triangles = {{0, 1, 2}};
  return mesh;
}

// A cube [-1, 1]^3 with 8 shared vertices and 12 outward (counter-clockwise) triangles.
std::shared_ptr<TriangleMesh> shared_cube() {
  auto mesh = std::make_shared<TriangleMesh>();
  for (int i = 0; i < 8; ++i)
    mesh->positions.push_back({(i & 1) ? 1.0 : -1.0, (i & 2) ? 1.0 : -1.0, (i & 4) ? 1.0 : -1.0});
  // Faces as quads (a, b, c, d) counter-clockwise from outside, split along a-c.
  const uint32_t quads[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
  for (const auto& q : quads) {
    mesh->triangles.push_back({q[0], q[1], q[2]});
    mesh->triangles.push_back({q[0], q[2], q[3]});
  }
  return mesh;
}

// The same cube with every face owning its four vertices (as OBJ exporters often write it).
std::shared_ptr<TriangleMesh> split_cube() {
  const auto shared = shared_cube();
  auto mesh = std::make_shared<TriangleMesh>();
  for (const auto& tri : shared->triangles) {
    std::array<uint32_t, 3> copy{};
    for (int k = 0; k < 3; ++k) {
      copy[k] = static_cast<uint32_t>(mesh->positions.size());
      mesh->positions.push_back(shared->positions[tri[k]]);
    }
    mesh->triangles.push_back(copy);
  }
  return mesh;
}

TEST(MeshTriangle, AnalyticHit) {
  const MeshTriangle triangle(unit_triangle(), 0);
  SurfaceHit hit;
  ASSERT_TRUE(triangle.intersect(make_ray({0.25, 0.25, 5}, {0, 0, -1}), hit));
  EXPECT_DOUBLE_EQ(hit.t, 5.0);
  expect_vec_near(hit.position, {0.25, 0.25, 0}, 1e-15);
  expect_vec_near(hit.object_position, hit.position, 0);
  expect_vec_near(hit.geometric_normal, {0, 0, 1}, 1e-15);
  expect_vec_near(hit.shading_normal, {0, 0, 1}, 1e-15);
  // Default corner uvs (0,0), (1,0), (1,1): barycentrics (0.5, 0.25, 0.25) give (0.5, 0.25).
  EXPECT_NEAR(hit.uv.x, 0.5, 1e-15);
  EXPECT_NEAR(hit.uv.y, 0.25, 1e-15);
  expect_vec_near(hit.dpdu, {1, 0, 0}, 1e-15);
  expect_vec_near(hit.dpdv, {-1, 1, 0}, 1e-15);
  EXPECT_GT(dot(cross(hit.dpdu, hit.dpdv), hit.geometric_normal), 0);
  EXPECT_EQ(triangle.type_name(), "triangle");
}

TEST(MeshTriangle, BarycentricsOfTheRawTest) {
  TriangleIntersection found;
  const Vec3 p0{1, 2, 3}, p1{4, 2, 3}, p2{1, 6, 3};
  // The point p0 + 0.2 (p1 - p0) + 0.5 (p2 - p0), approached obliquely from below.
  const Vec3 target = p0 + (p1 - p0) * 0.2 + (p2 - p0) * 0.5;
  const Vec3 origin{-1, 0, -2};
  ASSERT_TRUE(intersect_triangle(make_ray(origin, target - origin), p0, p1, p2, found));
  EXPECT_NEAR(found.t, length(target - origin), 1e-12);
  EXPECT_NEAR(found.b0, 0.3, 1e-12);
  EXPECT_NEAR(found.b1, 0.2, 1e-12);
  EXPECT_NEAR(found.b2, 0.5, 1e-12);
  EXPECT_DOUBLE_EQ(found.b0 + found.b1 + found.b2, 1.0);
}

TEST(MeshTriangle, HitFromBehindIsTwoSidedWithTheSameNormal) {
  const MeshTriangle triangle(unit_triangle(), 0);
  SurfaceHit hit;
  ASSERT_TRUE(triangle.intersect(make_ray({0.1, 0.2, -3}, {0, 0, 1}), hit));
  EXPECT_DOUBLE_EQ(hit.t, 3.0);
  expect_vec_near(hit.geometric_normal, {0, 0, 1}, 1e-15);  // the winding decides, not the ray
}

TEST(MeshTriangle, Misses) {
  const MeshTriangle triangle(unit_triangle(), 0);
  SurfaceHit hit;
  EXPECT_FALSE(triangle.intersect(make_ray({0.6, 0.6, 1}, {0, 0, -1}), hit));  // beyond p1-p2
  EXPECT_FALSE(triangle.intersect(make_ray({-0.1, 0.5, 1}, {0, 0, -1}), hit));
  EXPECT_FALSE(triangle.intersect(make_ray({0.5, -0.1, 1}, {0, 0, -1}), hit));
  EXPECT_FALSE(triangle.occluded(make_ray({0.6, 0.6, 1}, {0, 0, -1})));
  // Parallel to the plane, inside it: edge-on, never a hit.
  EXPECT_FALSE(triangle.intersect(make_ray({-1, 0.25, 0}, {1, 0, 0}), hit));
  // Parallel above it.
  EXPECT_FALSE(triangle.intersect(make_ray({-1, 0.25, 0.5}, {1, 0, 0}), hit));
}

TEST(MeshTriangle, TriangleBehindTheOriginIsMissed) {
  const MeshTriangle triangle(unit_triangle(), 0);
  SurfaceHit hit;
  EXPECT_FALSE(triangle.intersect(make_ray({0.25, 0.25, -1}, {0, 0, -1}), hit));
  EXPECT_FALSE(triangle.occluded(make_ray({0.25, 0.25, -1}, {0, 0, -1})));
}

TEST(MeshTriangle, HonoursTMinAndTMaxStrictly) {
  const MeshTriangle triangle(unit_triangle(), 0);
  SurfaceHit hit;
  Ray ray = make_ray({0.25, 0.25, 2}, {0, 0, -1});
  ray.t_max = 2.0;  // t == t_max is not accepted
  EXPECT_FALSE(triangle.intersect(ray, hit));
  EXPECT_FALSE(triangle.occluded(ray));
  ray.t_max = std::nextafter(2.0, 3.0);
  EXPECT_TRUE(triangle.intersect(ray, hit));
  EXPECT_TRUE(triangle.occluded(ray));
  ray.t_max = kInfinity;
  ray.t_min = 2.0;  // t == t_min is not accepted either
  EXPECT_FALSE(triangle.intersect(ray, hit));
  ray.t_min = std::nextafter(2.0, 0.0);
  EXPECT_TRUE(triangle.intersect(ray, hit));
  // A ray starting on the triangle with a small t_min does not hit it.
  Ray on_surface = make_ray({0.25, 0.25, 0}, {0, 0, 1});
  on_surface.t_min = 1e-9;
  EXPECT_FALSE(triangle.intersect(on_surface, hit));
}

TEST(MeshTriangle, DegenerateTrianglesNeverHitAndAreSkipped) {
  auto mesh = std::make_shared<TriangleMesh>();
  mesh->positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 0, 0}, {0.5, 0.5, 0}};
  mesh->triangles = {{0, 1, 2},   // fine
                     {0, 1, 3},   // collinear
                     {1, 1, 2},   // repeated index
                     {1, 4, 2}};  // (0.5, 0.5) lies on the edge p1-p2: collinear
  EXPECT_FALSE(mesh->is_degenerate(0));
  EXPECT_TRUE(mesh->is_degenerate(1));
  EXPECT_TRUE(mesh->is_degenerate(2));
  EXPECT_TRUE(mesh->is_degenerate(3));
  SurfaceHit hit;
  for (uint32_t t = 1; t < 4; ++t) {
    const MeshTriangle degenerate(mesh, t);
    // Straight through the segment the triangle collapses to, and obliquely.
    EXPECT_FALSE(degenerate.intersect(make_ray({0.5, 0, 1}, {0, 0, -1}), hit)) << t;
    EXPECT_FALSE(degenerate.intersect(make_ray({0.5, 0.5, 1}, {0, 0, -1}), hit)) << t;
    EXPECT_FALSE(degenerate.intersect(make_ray({0.5, -1, 1}, {0, 1, -1}), hit)) << t;
    EXPECT_FALSE(degenerate.occluded(make_ray({0.5, 0, 1}, {0, 0, -1}))) << t;
  }
  std::size_t skipped = 99;
  const auto shapes = make_triangles(mesh, &skipped);
  EXPECT_EQ(shapes.size(), 1u);
  EXPECT_EQ(skipped, 3u);
  EXPECT_EQ(dynamic_cast<const MeshTriangle&>(*shapes[0]).triangle_index(), 0u);
  EXPECT_EQ(make_triangles(mesh).size(), 1u);  // the count is optional
}

TEST(MeshTriangle, RejectsBadIndicesAndSizes) {
  auto mesh = unit_triangle();
  EXPECT_THROW(MeshTriangle(mesh, 1), std::invalid_argument);
  EXPECT_THROW(MeshTriangle(nullptr, 0), std::invalid_argument);
  mesh->triangles.push_back({0, 1, 7});
  EXPECT_THROW(MeshTriangle(mesh, 1), std::invalid_argument);
  EXPECT_THROW(make_triangles(mesh), std::invalid_argument);
  mesh->triangles.pop_back();
  mesh->corner_uvs.resize(2);
  EXPECT_THROW(MeshTriangle(mesh, 0), std::invalid_argument);
  EXPECT_THROW(mesh->validate(), std::invalid_argument);
  mesh->corner_uvs.clear();
  mesh->positions[1].x = std::nan("");
  EXPECT_THROW(mesh->validate(), std::invalid_argument);
}

TEST(MeshTriangle, BoundsCoverTheCorners) {
  auto mesh = std::make_shared<TriangleMesh>();
  mesh->positions = {{1, -2, 3}, {4, 5, -6}, {-7, 8, 9}};
  mesh->triangles = {{0, 1, 2}};
  const Bounds3 bounds = MeshTriangle(mesh, 0).bounds();
  expect_vec_near(bounds.lower, {-7, -2, -6}, 0);
  expect_vec_near(bounds.upper, {4, 8, 9}, 0);
}

TEST(MeshTriangle, CornerUvsGiveUvAndDerivatives) {
  auto mesh = unit_triangle();
  mesh->corner_uvs = {{Vec2{0, 0}, Vec2{2, 0}, Vec2{0, 3}}};
  const MeshTriangle triangle(mesh, 0);
  SurfaceHit hit;
  ASSERT_TRUE(triangle.intersect(make_ray({0.25, 0.5, 1}, {0, 0, -1}), hit));
  EXPECT_NEAR(hit.uv.x, 0.5, 1e-15);  // u = 2 b1
  EXPECT_NEAR(hit.uv.y, 1.5, 1e-15);  // v = 3 b2
  expect_vec_near(hit.dpdu, {0.5, 0, 0}, 1e-15);
  expect_vec_near(hit.dpdv, {0, 1.0 / 3.0, 0}, 1e-15);

  // All corners share one uv: the determinant vanishes, fall back to a basis around the normal.
  mesh->corner_uvs = {{Vec2{0.5, 0.5}, Vec2{0.5, 0.5}, Vec2{0.5, 0.5}}};
  ASSERT_TRUE(triangle.intersect(make_ray({0.25, 0.5, 1}, {0, 0, -1}), hit));
  EXPECT_NEAR(hit.uv.x, 0.5, 1e-15);
  EXPECT_NEAR(length(hit.dpdu), 1.0, 1e-12);
  EXPECT_NEAR(length(hit.dpdv), 1.0, 1e-12);
  EXPECT_NEAR(dot(hit.dpdu, hit.dpdv), 0.0, 1e-12);
  expect_vec_near(cross(hit.dpdu, hit.dpdv), hit.geometric_normal, 1e-12);
}

// fill_triangle_hit writes the default uvs' solve out (a fifth of its instructions); it must give
// the bits the general solve gives with kDefaultCornerUvs as the mesh's own uvs, signed zeros and
// NaN included: corners on a small grid (equal coordinates make the differences +0 or -0), in
// general position and a few that overflow, are NaN or collapse; weights that are 0, -0,
// negative, NaN or ordinary.
TEST(MeshTriangle, DefaultUvsGiveTheGeneralSolvesBits) {
  const auto same_bits = [](double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; };
  const double weights[] = {0.0, -0.0, 1.0, 0.25, -1e-17, 0.5, std::numeric_limits<double>::quiet_NaN()};
  // And corners that make the solve overflow, or NaN, or collapse (the fallback basis).
  constexpr double kInf = std::numeric_limits<double>::infinity();
  const Vec3 special[][3] = {{{kInf, 0, 0}, {0, 1, 0}, {1, 0, 0}},
                             {{std::numeric_limits<double>::quiet_NaN(), 0, 0}, {0, 1, 0}, {1, 0, 0}},
                             {{1e300, 1e300, 0}, {-1e300, 0, 0}, {0, 1e300, 0}},
                             {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}},
                             {{-0.0, 1e-310, 0}, {0, -0.0, 5e-324}, {1e-310, 0, -0.0}}};
  constexpr int kSpecial = sizeof special / sizeof special[0];
  Pcg32 rng(26, 7);
  int compared = 0;
  for (int trial = 0; trial < 400 + kSpecial; ++trial) {
    auto implicit = std::make_shared<TriangleMesh>();
    for (int v = 0; v < 3; ++v) {
      Vec3 p;
      for (int axis = 0; axis < 3; ++axis)
        p[axis] = trial % 2 == 0 ? static_cast<double>(rng.next_uint() % 3) - 1.0 : rng.next_double() * 4 - 2;
      implicit->positions.push_back(trial < 400 ? p : special[trial - 400][v]);
    }
    implicit->triangles = {{0, 1, 2}};
    auto explicit_uvs = std::make_shared<TriangleMesh>(*implicit);
    explicit_uvs->corner_uvs = {kDefaultCornerUvs};
    const Vec3 &p0 = implicit->positions[0], &p1 = implicit->positions[1], &p2 = implicit->positions[2];
    for (double b1 : weights) {
      for (double b2 : weights) {
        const TriangleIntersection found{1.5, 1.0 - b1 - b2, b1, b2};
        SurfaceHit a, b;
        fill_triangle_hit(*implicit, 0, p0, p1, p2, found, a);
        fill_triangle_hit(*explicit_uvs, 0, p0, p1, p2, found, b);
        const double a_values[] = {a.uv.x,   a.uv.y,   a.dpdu.x, a.dpdu.y,
                                   a.dpdu.z, a.dpdv.x, a.dpdv.y, a.dpdv.z};
        const double b_values[] = {b.uv.x,   b.uv.y,   b.dpdu.x, b.dpdu.y,
                                   b.dpdu.z, b.dpdv.x, b.dpdv.y, b.dpdv.z};
        for (int k = 0; k < 8; ++k)
          EXPECT_TRUE(same_bits(a_values[k], b_values[k]))
              << "trial " << trial << " b1 " << b1 << " b2 " << b2 << " value " << k << ": " << a_values[k]
              << " vs " << b_values[k];
        ++compared;
      }
    }
  }
  EXPECT_EQ(compared, (400 + kSpecial) * 49);
}

TEST(MeshTriangle, ShadingNormalInterpolatesCornerNormals) {
  auto mesh = unit_triangle();
  const Vec3 n0{0, 0, 1};
  const Vec3 n1 = normalize(Vec3{1, 0, 1});
  const Vec3 n2 = normalize(Vec3{0, 1, 1});
  mesh->corner_normals = {{n0, n1, n2}};
  const MeshTriangle triangle(mesh, 0);
  SurfaceHit hit;
  ASSERT_TRUE(triangle.intersect(make_ray({0.25, 0.25, 1}, {0, 0, -1}), hit));
  expect_vec_near(hit.shading_normal, normalize(n0 * 0.5 + n1 * 0.25 + n2 * 0.25), 1e-15);
  expect_vec_near(hit.geometric_normal, {0, 0, 1}, 1e-15);
  // At a corner the shading normal is that corner's normal.
  ASSERT_TRUE(triangle.intersect(make_ray({1 - 1e-12, 1e-13, 1}, {0, 0, -1}), hit));
  expect_vec_near(hit.shading_normal, n1, 1e-9);
  // Cancelling normals fall back to the geometric one.
  mesh->corner_normals = {{Vec3{0, 0, 1}, Vec3{0, 0, -1}, Vec3{0, 0, 0}}};
  ASSERT_TRUE(triangle.intersect(make_ray({0.4, 0.2, 1}, {0, 0, -1}), hit));  // b0 = b1 = 0.4
  EXPECT_TRUE(is_finite(hit.shading_normal));
  EXPECT_NEAR(length(hit.shading_normal), 1.0, 1e-12);
}

// Watertightness: rays aimed exactly at a shared edge never slip between the two triangles.
TEST(MeshTriangle, WatertightAlongTheDiagonalOfAQuad) {
  Pcg32 rng(7, 1);
  // An irregular, slightly non-planar quad (a, b, c, d) split along a-c.
  const Vec3 a{0.1234567, -0.3141592, 0.2718281};
  const Vec3 b{1.4142135, 0.1732050, 0.3333333};
  const Vec3 c{1.2360679, 1.6180339, 0.1111111};
  const Vec3 d{-0.2718281, 1.0471975, 0.4444444};
  auto mesh = std::make_shared<TriangleMesh>();
  mesh->positions = {a, b, c, d};
  mesh->triangles = {{0, 1, 2}, {0, 2, 3}};
  const MeshTriangle first(mesh, 0), second(mesh, 1);
  int holes = 0, double_hits = 0, tested = 0;
  const int rays = 200000;
  for (int i = 0; i < rays; ++i) {
    // A fan from a random origin above or below, aimed at points along the diagonal.
    const double s = 1e-6 + (1 - 2e-6) * rng.next_double();
    const Vec3 target = a + (c - a) * s;
    const double side = (i % 2 == 0) ? 1.0 : -1.0;
    const Vec3 origin{4 * rng.next_double() - 1.5, 4 * rng.next_double() - 1.5,
                      side * (0.5 + 3 * rng.next_double())};
    // Only where the diagonal is not a silhouette seen from the origin (b and d on opposite
    // sides of the plane through the origin and the diagonal); there a ray must hit.
    const Vec3 plane = cross(a - origin, c - origin);
    const double side_b = dot(plane, b - origin), side_d = dot(plane, d - origin);
    if (!(side_b * side_d < 0) || std::fabs(side_b) < 1e-3 || std::fabs(side_d) < 1e-3) continue;
    ++tested;
    const Ray ray = make_ray(origin, target - origin);
    const bool hit_first = first.occluded(ray);
    const bool hit_second = second.occluded(ray);
    if (!hit_first && !hit_second) ++holes;
    if (hit_first && hit_second) ++double_hits;
    // intersect agrees with occluded.
    if (i % 1000 == 0) {
      SurfaceHit hit;
      EXPECT_EQ(first.intersect(ray, hit), hit_first);
    }
  }
  EXPECT_GT(tested, rays / 2);
  EXPECT_EQ(holes, 0) << "rays falling through the shared edge out of " << tested;
  RecordProperty("double_hits", double_hits);
}

TEST(MeshTriangle, WatertightAtTheSharedVertexOfAFan) {
  // A fan of 7 triangles around a slightly raised centre, irregular ring.
  Pcg32 rng(11, 3);
  auto mesh = std::make_shared<TriangleMesh>();
  const Vec3 centre{0.3183098, -0.1591549, 0.05};
  mesh->positions.push_back(centre);
  const int ring = 7;
  for (int k = 0; k < ring; ++k) {
    const double angle = 2 * kPi * (k + 0.3 * rng.next_double()) / ring;
    const double radius = 0.7 + 0.6 * rng.next_double();
    mesh->positions.push_back({centre.x + radius * std::cos(angle), centre.y + radius * std::sin(angle),
                               0.1 * rng.next_double() - 0.05});
  }
  for (int k = 0; k < ring; ++k)
    mesh->triangles.push_back({0u, static_cast<uint32_t>(1 + k), static_cast<uint32_t>(1 + (k + 1) % ring)});
  std::size_t skipped = 0;
  const auto shapes = make_triangles(mesh, &skipped);
  ASSERT_EQ(shapes.size(), static_cast<std::size_t>(ring));
  int holes = 0;
  const int rays = 50000;
  for (int i = 0; i < rays; ++i) {
    // Within ~40 degrees of the vertical, from above and below, at the vertex or a hair off it.
    const double side = (i % 2 == 0) ? 1.0 : -1.0;
    const Vec3 origin = centre + Vec3{1.6 * rng.next_double() - 0.8, 1.6 * rng.next_double() - 0.8,
                                      side * (1 + rng.next_double())};
    Vec3 target = centre;
    if (i % 4 >= 2) target += Vec3{rng.next_double() - 0.5, rng.next_double() - 0.5, 0} * 1e-14;
    const Ray ray = make_ray(origin, target - origin);
    bool any = false;
    for (const auto& shape : shapes) any = any || shape->occluded(ray);
    if (!any) ++holes;
  }
  EXPECT_EQ(holes, 0) << "rays falling through the shared vertex out of " << rays;
}

TEST(MeshTriangle, WatertightOnAnAxisAlignedDiagonal) {
  // Rays exactly down the diagonal of an axis-aligned quad: the edge functions are exactly zero.
  auto mesh = std::make_shared<TriangleMesh>();
  mesh->positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  mesh->triangles = {{0, 1, 2}, {0, 2, 3}};
  const MeshTriangle first(mesh, 0), second(mesh, 1);
  for (int i = 1; i < 1000; ++i) {
    const double s = i / 1000.0;
    const Ray ray = make_ray({s, s, 1}, {0, 0, -1});
    EXPECT_TRUE(first.occluded(ray) || second.occluded(ray)) << s;
  }
}

// -------------------------------------------------------------------------------------------
// Smooth normals

TEST(TriangleMesh, CreaseAngleKeepsCubeEdgesSharp) {
  for (const auto& mesh : {shared_cube(), split_cube()}) {
    compute_corner_normals(*mesh, 30.0);
    ASSERT_EQ(mesh->corner_normals.size(), mesh->triangles.size());
    for (std::size_t t = 0; t < mesh->triangles.size(); ++t) {
      const Vec3 face = normalize(mesh->face_cross(t));
      for (const Vec3& n : mesh->corner_normals[t]) expect_vec_near(n, face, 1e-15);
    }
  }
}

TEST(TriangleMesh, CreaseAngle180AveragesAroundEachVertex) {
  for (const auto& mesh : {shared_cube(), split_cube()}) {
    compute_corner_normals(*mesh, 180.0);
    // Every corner at the same position has the same normal, pointing into the octant of that
    // cube corner (area-weighted, so not exactly the diagonal: a face split into two triangles
    // at that corner counts twice).
    std::map<std::tuple<double, double, double>, Vec3> seen;
    for (std::size_t t = 0; t < mesh->triangles.size(); ++t) {
      for (int k = 0; k < 3; ++k) {
        const Vec3& p = mesh->positions[mesh->triangles[t][k]];
        const Vec3& n = mesh->corner_normals[t][k];
        EXPECT_NEAR(length(n), 1.0, 1e-14);
        EXPECT_GT(dot(n, normalize(p)), 0.9);
        EXPECT_GT(n.x * p.x, 0);
        EXPECT_GT(n.y * p.y, 0);
        EXPECT_GT(n.z * p.z, 0);
        const auto key = std::make_tuple(p.x, p.y, p.z);
        const auto [it, inserted] = seen.emplace(key, n);
        if (!inserted) expect_vec_near(n, it->second, 1e-15);
      }
    }
    EXPECT_EQ(seen.size(), 8u);
  }
}

TEST(TriangleMesh, SmoothPrismSideKeepsItsCapFlat) {
  // A hexagonal prism side (12 triangles) and a top cap fan. Adjacent side faces meet at 60
  // degrees, the cap meets the side at 90: crease 61 smooths the side but not the cap edge,
  // crease 45 smooths nothing.
  auto mesh = std::make_shared<TriangleMesh>();
  const int sides = 6;
  for (int k = 0; k < sides; ++k) {
    const double angle = 2 * kPi * k / sides;
    mesh->positions.push_back({std::cos(angle), std::sin(angle), 0});
    mesh->positions.push_back({std::cos(angle), std::sin(angle), 1});
  }
  mesh->positions.push_back({0, 0, 1});  // cap centre, index 12
  for (uint32_t k = 0; k < sides; ++k) {
    const uint32_t b0 = 2 * k, t0 = 2 * k + 1, b1 = 2 * ((k + 1) % sides), t1 = 2 * ((k + 1) % sides) + 1;
    mesh->triangles.push_back({b0, b1, t1});
    mesh->triangles.push_back({b0, t1, t0});
    mesh->triangles.push_back({12, t0, t1});  // cap, normal +z
  }
  compute_corner_normals(*mesh, 61.0);
  std::map<uint32_t, Vec3> side_normal;
  for (std::size_t t = 0; t < mesh->triangles.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const Vec3& n = mesh->corner_normals[t][k];
      const uint32_t vertex = mesh->triangles[t][k];
      const Vec3& p = mesh->positions[vertex];
      if (t % 3 == 2) {
        expect_vec_near(n, {0, 0, 1}, 1e-15);  // the cap stays flat
        continue;
      }
      // The side is smooth: horizontal, close to radial (area weighting makes it lean a little
      // towards the face that has two triangles at this vertex), the same for every corner.
      EXPECT_NEAR(n.z, 0.0, 1e-15);
      EXPECT_NEAR(length(n), 1.0, 1e-14);
      EXPECT_GT(dot(n, normalize(Vec3{p.x, p.y, 0})), std::cos(degrees_to_radians(30)));
      EXPECT_LT(dot(n, normalize(mesh->face_cross(t))), 0.999);
      const auto [it, inserted] = side_normal.emplace(vertex, n);
      if (!inserted) expect_vec_near(n, it->second, 1e-15);
    }
  }
  compute_corner_normals(*mesh, 45.0);
  for (std::size_t t = 0; t < mesh->triangles.size(); t += 3) {
    const Vec3 face = normalize(mesh->face_cross(t));
    for (const Vec3& n : mesh->corner_normals[t]) expect_vec_near(n, face, 1e-14);
  }
}

TEST(TriangleMesh, ComputeCornerNormalsHandlesDegenerateTriangles) {
  auto mesh = unit_triangle();
  mesh->positions.push_back({2, 0, 0});
  mesh->triangles.push_back({0, 1, 3});  // collinear
  compute_corner_normals(*mesh, 180);
  expect_vec_near(mesh->corner_normals[0][0], {0, 0, 1}, 1e-15);
  EXPECT_TRUE(is_finite(mesh->corner_normals[1][0]));
  EXPECT_THROW(compute_corner_normals(*mesh, -1), std::invalid_argument);
  EXPECT_THROW(compute_corner_normals(*mesh, std::nan("")), std::invalid_argument);
}

TEST(TriangleMesh, SmoothCubeHitHasInterpolatedShadingNormal) {
  auto mesh = shared_cube();
  compute_corner_normals(*mesh, 180);
  const auto shapes = make_triangles(mesh);
  ASSERT_EQ(shapes.size(), 12u);
  // Near the corner (1, 1, 1) of the +z face the shading normal leans towards the diagonal.
  const Ray ray = make_ray({0.999, 0.999, 5}, {0, 0, -1});
  SurfaceHit nearest;
  nearest.t = kInfinity;
  bool any = false;
  for (const auto& shape : shapes) {
    SurfaceHit hit;
    if (shape->intersect(ray, hit) && hit.t < nearest.t) {
      nearest = hit;
      any = true;
    }
  }
  ASSERT_TRUE(any);
  EXPECT_NEAR(nearest.t, 4.0, 1e-12);
  expect_vec_near(nearest.geometric_normal, {0, 0, 1}, 1e-15);
  EXPECT_GT(nearest.shading_normal.x, 0.3);
  EXPECT_GT(nearest.shading_normal.y, 0.3);
  EXPECT_LT(nearest.shading_normal.z, 0.9);
}

// -------------------------------------------------------------------------------------------
// Transforms

TEST(TriangleMesh, TransformMovesPositionsAndNormals) {
  auto mesh = unit_triangle();
  const Vec3 tilted = normalize(Vec3{1, 0, 1});
  mesh->corner_normals = {{tilted, tilted, tilted}};
  mesh->transform(Transform::translate({10, 0, 0}) * Transform::scale({2, 1, 1}));
  expect_vec_near(mesh->positions[0], {10, 0, 0}, 0);
  expect_vec_near(mesh->positions[1], {12, 0, 0}, 0);
  expect_vec_near(mesh->positions[2], {10, 1, 0}, 0);
  // Normals by the inverse transpose: (1, 0, 1) -> (1/2, 0, 1), renormalised.
  expect_vec_near(mesh->corner_normals[0][0], normalize(Vec3{0.5, 0, 1}), 1e-15);
  const MeshTriangle triangle(mesh, 0);
  SurfaceHit hit;
  ASSERT_TRUE(triangle.intersect(make_ray({11, 0.25, 3}, {0, 0, -1}), hit));
  EXPECT_DOUBLE_EQ(hit.t, 3.0);
  expect_vec_near(hit.position, {11, 0.25, 0}, 1e-14);
  expect_vec_near(hit.geometric_normal, {0, 0, 1}, 1e-15);
  expect_vec_near(hit.shading_normal, normalize(Vec3{0.5, 0, 1}), 1e-15);
  const Bounds3 bounds = mesh->bounds();
  expect_vec_near(bounds.lower, {10, 0, 0}, 0);
  expect_vec_near(bounds.upper, {12, 1, 0}, 0);
}

TEST(TriangleMesh, RotationKeepsNormalsUnit) {
  auto mesh = shared_cube();
  compute_corner_normals(*mesh, 30);
  mesh->transform(Transform::rotate(90, {0, 0, 1}));
  // The +x face's normal is now +y.
  for (std::size_t t = 0; t < mesh->triangles.size(); ++t) {
    const Vec3 face = normalize(mesh->face_cross(t));
    for (const Vec3& n : mesh->corner_normals[t]) expect_vec_near(n, face, 1e-12);
  }
}

TEST(TriangleMesh, MirroringTransformKeepsNormalsOutward) {
  auto mesh = shared_cube();
  compute_corner_normals(*mesh, 30);
  mesh->transform(Transform::translate({5, 0, 0}) * Transform::scale({-1, 2, 1}));
  const auto shapes = make_triangles(mesh);
  // Every face normal points away from the centre (5, 0, 0) and agrees with its corner normals.
  for (std::size_t t = 0; t < mesh->triangles.size(); ++t) {
    const Vec3 face = normalize(mesh->face_cross(t));
    const Bounds3 b = mesh->triangle_bounds(t);
    EXPECT_GT(dot(face, b.center() - Vec3{5, 0, 0}), 0) << t;
    for (const Vec3& n : mesh->corner_normals[t]) expect_vec_near(n, face, 1e-12);
  }
  // A ray from +x hits the x = 6 face with an outward normal.
  SurfaceHit nearest;
  nearest.t = kInfinity;
  for (const auto& shape : shapes) {
    SurfaceHit hit;
    if (shape->intersect(make_ray({10, 0.5, 0.5}, {-1, 0, 0}), hit) && hit.t < nearest.t) nearest = hit;
  }
  EXPECT_NEAR(nearest.t, 4.0, 1e-12);
  expect_vec_near(nearest.geometric_normal, {1, 0, 0}, 1e-15);
}

// Copies of a triangle (the same corners in the same cyclic order, through the same
// or other vertices) are left out by make_triangles when asked, and counted; the reversed
// winding and degenerate triangles are not copies.
TEST(TriangleMesh, RepeatedTrianglesAreMergedIntoTheFirst) {
  auto mesh = std::make_shared<TriangleMesh>();
  mesh->positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 0}, {-0.0, 0, 0}};
  mesh->triangles = {{0, 1, 2}, {1, 2, 0}, {2, 1, 0}, {3, 1, 2}, {0, 1, 1}, {4, 1, 2}, {0, 0, 0}};
  const std::vector<bool> repeated = repeated_triangles(*mesh);
  EXPECT_EQ(repeated, (std::vector<bool>{false, true, false, true, false, true, false}));
  std::size_t skipped = 0, merged = 0;
  const auto shapes = make_triangles(mesh, &skipped, &merged);
  ASSERT_EQ(shapes.size(), 2u);
  EXPECT_EQ(static_cast<const MeshTriangle&>(*shapes[0]).triangle_index(), 0u);
  EXPECT_EQ(static_cast<const MeshTriangle&>(*shapes[1]).triangle_index(), 2u);
  EXPECT_EQ(skipped, 2u);
  EXPECT_EQ(merged, 3u);
  EXPECT_EQ(make_triangles(mesh).size(), 5u);  // not asked: every non-degenerate triangle
}

// The shear's axes, now chosen without branches: z is max_dimension(abs(direction)) (the later
// axis on a tie), x and y follow it cyclically and swap when the direction along z is negative
// (below zero: -0 does not swap); the shear factors are the directions' quotients.
TEST(WatertightRay, AxesFollowTheDominantDirectionAndItsSign) {
  std::vector<Vec3> directions;
  const double values[] = {-2.0, -1.0, -0.0, 0.0, 0.5, 1.0, 2.0};
  for (double x : values)
    for (double y : values)
      for (double z : values) directions.push_back({x, y, z});
  Pcg32 rng(7, 3);
  for (int i = 0; i < 200; ++i)
    directions.push_back({rng.next_double() - 0.5, rng.next_double() - 0.5, rng.next_double() - 0.5});
  for (const Vec3& d : directions) {
    Ray ray;
    ray.direction = d;
    const WatertightRay sheared(ray);
    const int kz = max_dimension(abs(d));
    int kx = (kz + 1) % 3, ky = (kx + 1) % 3;
    if (d[kz] < 0) std::swap(kx, ky);
    EXPECT_EQ(sheared.kz, kz) << d.x << " " << d.y << " " << d.z;
    EXPECT_EQ(sheared.kx, kx) << d.x << " " << d.y << " " << d.z;
    EXPECT_EQ(sheared.ky, ky) << d.x << " " << d.y << " " << d.z;
    if (d[kz] != 0) {
      EXPECT_EQ(sheared.sx, d[kx] / d[kz]);
      EXPECT_EQ(sheared.sy, d[ky] / d[kz]);
      EXPECT_EQ(sheared.sz, 1.0 / d[kz]);
    }
  }
}

}  // namespace
}  // namespace candela
