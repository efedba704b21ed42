// Shape::tessellate for every shape (SPEC §9, §10): areas converge to the analytic ones, vertices
// lie on the surface, triangles wind about the normal the ray test reports, corner uvs are the
// ray hits' uvs, closed shapes are watertight, and the plane is cut exactly by the clip box.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "geometry/box.h"
#include "geometry/cone.h"
#include "geometry/cylinder.h"
#include "geometry/disc.h"
#include "geometry/plane.h"
#include "geometry/polygon.h"
#include "geometry/quad.h"
#include "geometry/sphere.h"
#include "geometry/torus.h"
#include "geometry/transformed_shape.h"
#include "geometry/triangle_mesh.h"
#include "math/constants.h"

namespace candela {
namespace {

TriangleMesh tessellated(const Shape& shape, int segments, const Bounds3& clip = {}, bool area_true = true) {
  TessellationSettings settings;
  settings.segments = segments;
  settings.area_true = area_true;
  settings.clip = clip;
  TriangleMesh mesh;
  shape.tessellate(settings, mesh);
  mesh.validate();
  return mesh;
}

Vec3 corner(const TriangleMesh& mesh, std::size_t triangle, int k) {
  return mesh.positions[mesh.triangles[triangle][k]];
}

Vec3 centroid(const TriangleMesh& mesh, std::size_t triangle) {
  return (corner(mesh, triangle, 0) + corner(mesh, triangle, 1) + corner(mesh, triangle, 2)) / 3.0;
}

double longest_edge(const TriangleMesh& mesh, std::size_t triangle) {
  double longest = 0;
  for (int k = 0; k < 3; ++k)
    longest = std::max(longest, length(corner(mesh, triangle, (k + 1) % 3) - corner(mesh, triangle, k)));
  return longest;
}

double total_area(const TriangleMesh& mesh) {
  double area = 0;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) area += 0.5 * length(mesh.face_cross(t));
  return area;
}

// Distances from the surfaces, 0 on them (their implicit forms made distance-like).
double distance_from_axis(const Vec3& p, const Vec3& base, const Vec3& unit_axis, double& height) {
  height = dot(p - base, unit_axis);
  return length(p - base - unit_axis * height);
}

double outside(double value, double low, double high) {
  return std::max({0.0, low - value, value - high});
}

// Side of a cone (a cylinder when the radii agree) from base to cap, plus its caps when given.
std::function<double(const Vec3&)> cone_residual(Vec3 base, double base_radius, Vec3 cap, double cap_radius,
                                                 bool capped) {
  return [=](const Vec3& p) {
    const double height = length(cap - base);
    const Vec3 axis = (cap - base) / height;
    double z;
    const double rho = distance_from_axis(p, base, axis, z);
    const double slope = (cap_radius - base_radius) / height;
    double best =
        std::fabs(rho - (base_radius + slope * z)) / std::sqrt(1 + slope * slope) + outside(z, 0, height);
    if (capped) {
      best = std::min(best, std::fabs(z) + outside(rho, 0, base_radius));
      best = std::min(best, std::fabs(z - height) + outside(rho, 0, cap_radius));
    }
    return best;
  };
}

std::function<double(const Vec3&)> flat_residual(Vec3 point, Vec3 normal) {
  return [=](const Vec3& p) { return std::fabs(dot(p - point, normalize(normal))); };
}

// One shape under test, with what is known about it.
struct Case {
  std::string name;
  std::function<std::unique_ptr<Shape>()> make;
  std::function<double(const Vec3&)> residual;
  double size;  // for relative tolerances
  bool closed;
  Bounds3 clip{};
};

std::shared_ptr<TriangleMesh> two_triangle_mesh() {
  auto mesh = std::make_shared<TriangleMesh>();
  mesh->positions = {{0, 0, 1}, {2, 0, 1.5}, {0.5, 1.5, 1}, {1, 2, 0}};
  mesh->triangles = {{0, 1, 2}, {1, 3, 2}};
  mesh->corner_uvs = {{Vec2{0.1, 0.2}, Vec2{0.9, 0.1}, Vec2{0.3, 0.8}},
                      {Vec2{0.9, 0.1}, Vec2{1, 1}, Vec2{0.3, 0.8}}};
  mesh->corner_normals = {{Vec3{0, 0, 1}, Vec3{0, 0, 1}, Vec3{0, 0, 1}},
                          {Vec3{0, 0, 1}, Vec3{0, 0, 1}, Vec3{0, 0, 1}}};
  return mesh;
}

const Bounds3 kClipBox{{-1, -1.5, -2}, {2, 1, 1.5}};

std::vector<Case> all_cases() {
  const Vec3 torus_axis = normalize(Vec3{0.3, 1, 0.2});
  const Transform mirror = Transform::translate({1, -2, 0.5}) * Transform::scale({-1, 1.5, 0.8});
  // Uniform, so that the ray test's uv near a pole (where u turns fast) is not thrown off by a
  // ray that is oblique in object space.
  const Transform uniform_mirror = Transform::rotate(30, {1, 2, 3}) * Transform::scale({-1.5, 1.5, 1.5});
  std::vector<Case> cases{
      {"sphere",
       [] {
         return std::make_unique<Sphere>(Vec3{0.5, -1, 2}, 1.5);
       },
       [](const Vec3& p) {
         return std::fabs(length(p - Vec3{0.5, -1, 2}) - 1.5);
       },
       1.5, true},
      {"cylinder",
       [] {
         return std::make_unique<Cylinder>(Vec3{1, 0, 0}, Vec3{1, 2, 1}, 0.7);
       },
       cone_residual({1, 0, 0}, 0.7, {1, 2, 1}, 0.7, true), 2, true},
      {"open cylinder",
       [] {
         return std::make_unique<Cylinder>(Vec3{0, 0, 0}, Vec3{0, 0, 2}, 1, false);
       },
       cone_residual({0, 0, 0}, 1, {0, 0, 2}, 1, false), 2, false},
      {"truncated cone",
       [] {
         return std::make_unique<Cone>(Vec3{0, 1, 0}, 1.2, Vec3{0.5, 2, 1}, 0.4);
       },
       cone_residual({0, 1, 0}, 1.2, {0.5, 2, 1}, 0.4, true), 2, true},
      {"pointed cone",
       [] {
         return std::make_unique<Cone>(Vec3{0, 0, 0}, 1, Vec3{0, 0, 1.5}, 0);
       },
       cone_residual({0, 0, 0}, 1, {0, 0, 1.5}, 0, true), 1.5, true},
      {"cone pointed at its base",
       [] {
         return std::make_unique<Cone>(Vec3{0, 0, 0}, 0, Vec3{1, 1, 0}, 0.8);
       },
       cone_residual({0, 0, 0}, 0, {1, 1, 0}, 0.8, true), 1.5, true},
      {"torus",
       [=] {
         return std::make_unique<Torus>(Vec3{1, 0, 0}, torus_axis, 2, 0.6);
       },
       [=](const Vec3& p) {
         double z;
         const double rho = distance_from_axis(p, {1, 0, 0}, torus_axis, z);
         return std::fabs(std::hypot(rho - 2, z) - 0.6);
       },
       2.6, true},
      {"disc",
       [] {
         return std::make_unique<Disc>(Vec3{0, 1, 0}, Vec3{1, 2, -1}, 1.5);
       },
       [](const Vec3& p) {
         return flat_residual({0, 1, 0}, {1, 2, -1})(p) + outside(length(p - Vec3{0, 1, 0}), 0, 1.5);
       },
       1.5, false},
      {"annulus",
       [] {
         return std::make_unique<Disc>(Vec3{0, 0, 0}, Vec3{0, 0, -1}, 1.5, 0.5);
       },
       [](const Vec3& p) { return std::fabs(p.z) + outside(length(p), 0.5, 1.5); }, 1.5, false},
      {"box",
       [] {
         return std::make_unique<Box>(Vec3{-1, 0, 2}, Vec3{1, 0.5, 5});
       },
       [](const Vec3& p) {
         const Vec3 lower{-1, 0, 2}, upper{1, 0.5, 5};
         double best = kInfinity;
         for (int axis = 0; axis < 3; ++axis) {
           double off_face = 0;
           for (int other = 0; other < 3; ++other)
             if (other != axis) off_face += outside(p[other], lower[other], upper[other]);
           best = std::min({best, std::fabs(p[axis] - lower[axis]) + off_face,
                            std::fabs(p[axis] - upper[axis]) + off_face});
         }
         return best;
       },
       3, true},
      {"quad",
       [] {
         return std::make_unique<Quad>(Vec3{1, 0, 0}, Vec3{2, 0, 1}, Vec3{1, 1, 0});
       },
       flat_residual({1, 0, 0}, cross(Vec3{2, 0, 1}, Vec3{1, 1, 0})), 3, false},
      {"L polygon",
       [] {
         return std::make_unique<Polygon>(
             std::vector<Vec3>{{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}, {1, 2, 0}, {0, 2, 0}});
       },
       flat_residual({0, 0, 0}, {0, 0, 1}), 2, false},
      {"plane",
       [] {
         return std::make_unique<Plane>(Vec3{0.5, 0, 0}, Vec3{1, 2, 0.5});
       },
       [](const Vec3& p) {
         return flat_residual({0.5, 0, 0}, {1, 2, 0.5})(p) + outside(p.x, -1, 2) + outside(p.y, -1.5, 1) +
                outside(p.z, -2, 1.5);
       },
       4, false, kClipBox},
      {"mesh triangle", [] { return std::make_unique<MeshTriangle>(two_triangle_mesh(), 1); },
       flat_residual({2, 0, 1.5}, cross(Vec3{-1, 2, -1.5}, Vec3{-1.5, 1.5, -0.5})), 2, false},
      {"mirrored sphere",
       [=] {
         return std::make_unique<TransformedShape>(std::make_unique<Sphere>(Vec3{0.3, 0, 0}, 1),
                                                   uniform_mirror);
       },
       [=](const Vec3& p) {
         return std::fabs(length(uniform_mirror.inverse().point(p) - Vec3{0.3, 0, 0}) - 1);
       },
       1.5, true},
      {"mirrored cone",
       [=] {
         return std::make_unique<TransformedShape>(
             std::make_unique<Cone>(Vec3{0, 0, 0}, 1, Vec3{0, 1, 0}, 0.5), mirror);
       },
       [=](const Vec3& p) {
         return cone_residual({0, 0, 0}, 1, {0, 1, 0}, 0.5, true)(mirror.inverse().point(p));
       },
       1.5, true},
      {"rotated plane",
       [] {
         return std::make_unique<TransformedShape>(std::make_unique<Plane>(Vec3{0, 0, 1}, Vec3{0, 0, 1}),
                                                   Transform::rotate(30, {1, 1, 0}));
       },
       [](const Vec3& p) {
         const Transform rotation = Transform::rotate(30, {1, 1, 0});
         return flat_residual(rotation.point({0, 0, 1}), rotation.vector({0, 0, 1}))(p) +
                outside(p.x, -1, 2) + outside(p.y, -1.5, 1) + outside(p.z, -2, 1.5);
       },
       4, false, kClipBox},
  };
  return cases;
}

// What the ray test reports at the point target of the triangle: a ray from outside, along the
// triangle's reverse normal, close enough to stay on this part of the surface.
bool hit_near(const Shape& shape, const TriangleMesh& mesh, std::size_t triangle, const Vec3& target,
              SurfaceHit& hit) {
  const Vec3 normal = normalize(mesh.face_cross(triangle));
  const double offset = 0.5 * longest_edge(mesh, triangle);
  if (!shape.intersect(Ray{target + normal * offset, -normal}, hit)) {
    ADD_FAILURE() << "no hit at " << target;
    return false;
  }
  EXPECT_LT(length(hit.position - target), offset) << "hit far from " << target;
  return true;
}

// Flat shapes' vertices lie on them; curved shapes' lie just off them, moved out by the area-true
// factor (tessellation.h: 1 + (2π/N)²/12 for a disc of N segments), within twice that.
TEST(Tessellation, VerticesLieOnTheSurfaceOrJustOffItToKeepTheArea) {
  const std::vector<std::string> curved{
      "sphere", "cylinder", "open cylinder", "truncated cone",  "pointed cone", "cone pointed at its base",
      "torus",  "disc",     "annulus",       "mirrored sphere", "mirrored cone"};
  for (const Case& c : all_cases()) {
    SCOPED_TRACE(c.name);
    const auto shape = c.make();
    const int segments = 24;
    const TriangleMesh mesh = tessellated(*shape, segments, c.clip);
    ASSERT_FALSE(mesh.triangles.empty());
    const bool is_curved = std::find(curved.begin(), curved.end(), c.name) != curved.end();
    const double turn = 2 * kPi / segments;
    const double tolerance = is_curved ? turn * turn / 6 * c.size : 1e-12 * c.size;
    double farthest = 0;
    for (const Vec3& p : mesh.positions) {
      EXPECT_LT(c.residual(p), tolerance) << p;
      farthest = std::max(farthest, c.residual(p));
    }
    if (is_curved) {
      EXPECT_GT(farthest, 1e-4 * c.size);  // really moved out
    }
    EXPECT_TRUE(mesh.corner_normals.empty());
    EXPECT_EQ(mesh.corner_uvs.size(), mesh.triangles.size());
    // No zero-area triangles, and no vertex that no triangle uses.
    std::vector<bool> used(mesh.positions.size());
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
      EXPECT_FALSE(mesh.is_degenerate(t)) << t;
      for (uint32_t index : mesh.triangles[t]) used[index] = true;
    }
    for (std::size_t i = 0; i < used.size(); ++i) EXPECT_TRUE(used[i]) << "vertex " << i;
  }
}

TEST(Tessellation, WindingFollowsTheGeometricNormalOfTheRayTest) {
  for (const Case& c : all_cases()) {
    SCOPED_TRACE(c.name);
    const auto shape = c.make();
    for (const int segments : {5, 24}) {
      const TriangleMesh mesh = tessellated(*shape, segments, c.clip);
      for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        SurfaceHit hit;
        if (!hit_near(*shape, mesh, t, centroid(mesh, t), hit)) continue;
        EXPECT_GT(dot(mesh.face_cross(t), hit.geometric_normal), 0) << "triangle " << t;
      }
    }
  }
}

// On the inscribed tessellation (vertices on the surface, area_true off); the area-true one is the
// same grid with the same uvs, its points moved out (checked here too).
TEST(Tessellation, CornerUvsAreTheRayHitUvs) {
  // At each corner, moved a millionth of the way towards the triangle's centroid: that keeps
  // the point inside the parameter domain (on the right side of a seam, off a pole or a rim),
  // where the ray test's uv must be the corners' uvs interpolated.
  constexpr double kNudge = 1e-6;
  for (const Case& c : all_cases()) {
    SCOPED_TRACE(c.name);
    const auto shape = c.make();
    const TriangleMesh mesh = tessellated(*shape, 12, c.clip, /*area_true=*/false);
    const TriangleMesh area_true = tessellated(*shape, 12, c.clip);
    EXPECT_EQ(area_true.triangles, mesh.triangles);
    ASSERT_EQ(area_true.corner_uvs.size(), mesh.corner_uvs.size());
    for (std::size_t t = 0; t < mesh.corner_uvs.size(); ++t)
      for (int k = 0; k < 3; ++k) {
        EXPECT_EQ(area_true.corner_uvs[t][k].x, mesh.corner_uvs[t][k].x) << t;
        EXPECT_EQ(area_true.corner_uvs[t][k].y, mesh.corner_uvs[t][k].y) << t;
      }
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
      const auto& uvs = mesh.corner_uvs[t];
      for (int k = 0; k < 3; ++k) {
        std::array<double, 3> weight{kNudge / 3, kNudge / 3, kNudge / 3};
        weight[k] += 1 - kNudge;
        Vec3 target;
        Vec2 expected;
        for (int i = 0; i < 3; ++i) {
          target += corner(mesh, t, i) * weight[i];
          expected.x += uvs[i].x * weight[i];
          expected.y += uvs[i].y * weight[i];
        }
        SurfaceHit hit;
        if (!hit_near(*shape, mesh, t, target, hit)) continue;
        EXPECT_NEAR(hit.uv.x, expected.x, 1e-7) << "triangle " << t << " corner " << k;
        EXPECT_NEAR(hit.uv.y, expected.y, 1e-7) << "triangle " << t << " corner " << k;
      }
    }
  }
}

// Every directed edge (after welding equal positions) at most once, and the ones without their
// reverse: none for a closed, manifold, consistently wound mesh.
std::vector<std::pair<Vec3, Vec3>> boundary_edges(const TriangleMesh& mesh) {
  std::vector<Vec3> welded_position;
  std::map<std::array<double, 3>, uint32_t> ids;
  const auto id = [&](const Vec3& p) {
    const auto [it, inserted] =
        ids.emplace(std::array<double, 3>{p.x, p.y, p.z}, static_cast<uint32_t>(ids.size()));
    if (inserted) welded_position.push_back(p);
    return it->second;
  };
  std::map<std::pair<uint32_t, uint32_t>, int> directed;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (int k = 0; k < 3; ++k) ++directed[{id(corner(mesh, t, k)), id(corner(mesh, t, (k + 1) % 3))}];
  }
  std::vector<std::pair<Vec3, Vec3>> boundary;
  for (const auto& [edge, count] : directed) {
    EXPECT_EQ(count, 1) << "edge used twice in one direction";
    if (directed.find({edge.second, edge.first}) == directed.end())
      boundary.push_back({welded_position[edge.first], welded_position[edge.second]});
  }
  return boundary;
}

std::size_t unmatched_edges(const TriangleMesh& mesh) {
  return boundary_edges(mesh).size();
}

TEST(Tessellation, ClosedShapesAreWatertight) {
  for (const Case& c : all_cases()) {
    if (!c.closed) continue;
    SCOPED_TRACE(c.name);
    const auto shape = c.make();
    for (const int segments : {3, 7, 32}) EXPECT_EQ(unmatched_edges(tessellated(*shape, segments)), 0u);
  }
  // An open cylinder has exactly its two rims as boundary.
  EXPECT_EQ(unmatched_edges(tessellated(Cylinder({0, 0, 0}, {0, 0, 1}, 1, false), 16)), 32u);
  EXPECT_EQ(unmatched_edges(tessellated(Disc({0, 0, 0}, {0, 0, 1}, 1, 0.5), 16)), 32u);
}

// Analytic areas of the curved shapes.
struct AreaCase {
  std::string name;
  std::function<std::unique_ptr<Shape>()> make;
  double area;
};

TEST(Tessellation, CurvedAreasAreTheSurfacesOwnAtEverySegmentCount) {
  const double slant = std::sqrt(2.0 * 2.0 + 0.8 * 0.8);
  const std::vector<AreaCase> cases{
      {"sphere",
       [] {
         return std::make_unique<Sphere>(Vec3{1, 2, 3}, 1.5);
       },
       4 * kPi * 1.5 * 1.5},
      {"capped cylinder",
       [] {
         return std::make_unique<Cylinder>(Vec3{0, 0, 0}, Vec3{0, 3, 0}, 0.5);
       },
       2 * kPi * 0.5 * 3 + 2 * kPi * 0.25},
      {"open cylinder",
       [] {
         return std::make_unique<Cylinder>(Vec3{0, 0, 0}, Vec3{1, 1, 1}, 2, false);
       },
       2 * kPi * 2 * std::sqrt(3.0)},
      {"truncated cone",
       [] {
         return std::make_unique<Cone>(Vec3{0, 0, 0}, 1.2, Vec3{0, 0, 2}, 0.4);
       },
       kPi * (1.2 + 0.4) * slant + kPi * (1.2 * 1.2 + 0.4 * 0.4)},
      {"open pointed cone",
       [] {
         return std::make_unique<Cone>(Vec3{0, 0, 0}, 1, Vec3{0, 0, 1.5}, 0, false);
       },
       kPi * 1 * std::sqrt(1 + 1.5 * 1.5)},
      {"torus",
       [] {
         return std::make_unique<Torus>(Vec3{0, 0, 0}, Vec3{0, 0, 1}, 2, 0.5);
       },
       4 * kPi * kPi * 2 * 0.5},
      {"disc",
       [] {
         return std::make_unique<Disc>(Vec3{0, 0, 0}, Vec3{1, 1, 1}, 2);
       },
       kPi * 4},
      {"annulus",
       [] {
         return std::make_unique<Disc>(Vec3{0, 0, 0}, Vec3{1, 1, 1}, 2, 1);
       },
       kPi * 3},
  };
  // The tessellation's area is the surface's at every segment count (inscribed, a disc
  // lost 2.55 % at 16 segments and a sphere 3.2 %, converging only as 1/N²).
  for (const AreaCase& c : cases) {
    SCOPED_TRACE(c.name);
    const auto shape = c.make();
    for (const int segments : {3, 5, 16, 32, 128})
      EXPECT_NEAR(total_area(tessellated(*shape, segments)) / c.area, 1, 1e-9) << segments << " segments";
  }
}

TEST(Tessellation, CountsPerShapeAndTheMinimumOfThreeSegments) {
  struct Expected {
    std::unique_ptr<Shape> shape;
    int segments;
    std::size_t triangles, vertices;
  };
  std::vector<Expected> expected;
  // Sphere: n longitudes × max(2, n/2) bands, one vertex per pole.
  expected.push_back({std::make_unique<Sphere>(Vec3{}, 1), 32, 2 * 32 * 15, 2 + 32 * 15});
  expected.push_back({std::make_unique<Sphere>(Vec3{}, 1), 5, 2 * 5 * 1, 2 + 5});
  expected.push_back({std::make_unique<Sphere>(Vec3{}, 1), 1, 2 * 3 * 1, 2 + 3});
  expected.push_back({std::make_unique<Sphere>(Vec3{}, 1), -4, 2 * 3 * 1, 2 + 3});
  // Cylinder: one band of n quads and a fan of n per cap.
  expected.push_back({std::make_unique<Cylinder>(Vec3{}, Vec3{0, 1, 0}, 1), 16, 2 * 16 + 2 * 16, 2 * 16 + 2});
  expected.push_back({std::make_unique<Cylinder>(Vec3{}, Vec3{0, 1, 0}, 1, false), 16, 2 * 16, 2 * 16});
  // Cones: pointed ones have one apex vertex and no cap there.
  expected.push_back({std::make_unique<Cone>(Vec3{}, 1, Vec3{0, 1, 0}, 0), 16, 16 + 16, 16 + 2});
  expected.push_back({std::make_unique<Cone>(Vec3{}, 1, Vec3{0, 1, 0}, 0.5), 2, 2 * 3 + 2 * 3, 2 * 3 + 2});
  // Torus: n around the ring × max(3, n/2) around the tube.
  expected.push_back({std::make_unique<Torus>(Vec3{}, Vec3{0, 0, 1}, 2, 1), 16, 2 * 16 * 8, 16 * 8});
  expected.push_back({std::make_unique<Torus>(Vec3{}, Vec3{0, 0, 1}, 2, 1), 4, 2 * 4 * 3, 4 * 3});
  // Disc: a fan about one centre; annulus: one ring of quads.
  expected.push_back({std::make_unique<Disc>(Vec3{}, Vec3{0, 0, 1}, 1), 16, 16, 17});
  expected.push_back({std::make_unique<Disc>(Vec3{}, Vec3{0, 0, 1}, 1, 0.5), 16, 32, 32});
  // Flat shapes ignore segments.
  expected.push_back({std::make_unique<Box>(Vec3{}, Vec3{1, 2, 3}), 3, 12, 8});
  expected.push_back({std::make_unique<Quad>(Vec3{}, Vec3{1, 0, 0}, Vec3{0, 1, 0}), 64, 2, 4});
  for (const Expected& e : expected) {
    SCOPED_TRACE(std::string(e.shape->type_name()) + " with " + std::to_string(e.segments) + " segments");
    const TriangleMesh mesh = tessellated(*e.shape, e.segments);
    EXPECT_EQ(mesh.triangles.size(), e.triangles);
    EXPECT_EQ(mesh.positions.size(), e.vertices);
  }
}

TEST(Tessellation, BoxQuadAndConvexPolygonAreExact) {
  const TriangleMesh box = tessellated(Box({-1, 0, 2}, {1, 0.5, 5}), 8);
  EXPECT_NEAR(total_area(box), 2 * (2 * 0.5 + 0.5 * 3 + 3 * 2), 1e-14);
  // Outward: each face's normal points away from the box's centre.
  for (std::size_t t = 0; t < box.triangles.size(); ++t)
    EXPECT_GT(dot(box.face_cross(t), centroid(box, t) - Vec3{0, 0.25, 3.5}), 0);

  const Quad quad({1, 0, 0}, {2, 0, 1}, {1, 1, 0});
  const TriangleMesh quad_mesh = tessellated(quad, 8);
  EXPECT_NEAR(total_area(quad_mesh), quad.area(), 1e-14);
  EXPECT_EQ(quad_mesh.corner_uvs[0][0].x, 0);
  EXPECT_EQ(quad_mesh.corner_uvs[0][2].x, 1);
  EXPECT_EQ(quad_mesh.corner_uvs[0][2].y, 1);

  // A regular hexagon, tilted: 3√3/2 s².
  std::vector<Vec3> hexagon;
  for (int k = 0; k < 6; ++k)
    hexagon.push_back({std::cos(k * kPi / 3), 0.6 * std::sin(k * kPi / 3), 0.8 * std::sin(k * kPi / 3)});
  const double side_squared = length_squared(hexagon[1] - hexagon[0]);
  const TriangleMesh hexagon_mesh = tessellated(Polygon(hexagon), 8);
  EXPECT_EQ(hexagon_mesh.triangles.size(), 4u);
  EXPECT_NEAR(total_area(hexagon_mesh), 1.5 * std::sqrt(3.0) * side_squared, 1e-14);
}

// Points strictly inside every triangle must be inside the polygon (by its own ray test), and
// the areas must add up to the polygon's: together no triangle pokes out or overlaps another.
void expect_triangulates(const Polygon& polygon, double area, std::size_t max_triangles) {
  const TriangleMesh mesh = tessellated(polygon, 8);
  EXPECT_LE(mesh.triangles.size(), max_triangles);
  EXPECT_NEAR(total_area(mesh), area, 1e-13 * area);
  const Vec3& normal = polygon.normal();
  const std::array<std::array<double, 3>, 4> samples{
      {{1 / 3.0, 1 / 3.0, 1 / 3.0}, {0.8, 0.1, 0.1}, {0.1, 0.8, 0.1}, {0.1, 0.1, 0.8}}};
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    EXPECT_GT(dot(mesh.face_cross(t), normal), 0) << t;
    for (const auto& weight : samples) {
      const Vec3 p =
          corner(mesh, t, 0) * weight[0] + corner(mesh, t, 1) * weight[1] + corner(mesh, t, 2) * weight[2];
      SurfaceHit hit;
      EXPECT_TRUE(polygon.intersect(Ray{p + normal, -normal}, hit)) << "triangle " << t << " leaves at " << p;
    }
  }
}

TEST(Tessellation, NonConvexPolygonsWithCollinearVertices) {
  // An L of area 3, then the same with extra vertices in the middle of two edges, in a tilted
  // plane; a U (area 5) whose two reflex corners lie on one line.
  expect_triangulates(Polygon({{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}, {1, 2, 0}, {0, 2, 0}}), 3, 4);
  const Transform tilt = Transform::rotate(35, {1, -2, 0.5});
  std::vector<Vec3> tilted_l;
  for (const Vec3& p : {Vec3{0, 0, 0}, Vec3{1, 0, 0}, Vec3{2, 0, 0}, Vec3{2, 1, 0}, Vec3{1, 1, 0},
                        Vec3{1, 2, 0}, Vec3{0, 2, 0}, Vec3{0, 1, 0}})
    tilted_l.push_back(tilt.point(p));
  expect_triangulates(Polygon(tilted_l), 3, 6);
  expect_triangulates(
      Polygon({{0, 0, 0}, {3, 0, 0}, {3, 2, 0}, {2, 2, 0}, {2, 1, 0}, {1, 1, 0}, {1, 2, 0}, {0, 2, 0}}), 5,
      6);
  // Clockwise as listed: the normal is -z and the triangles follow it.
  expect_triangulates(Polygon({{0, 0, 0}, {0, 2, 0}, {1, 2, 0}, {1, 1, 0}, {2, 1, 0}, {2, 0, 0}}), 3, 4);
}

TEST(Tessellation, PlaneIsCutByTheClipBoxExactly) {
  const Bounds3 unit{{0, 0, 0}, {1, 1, 1}};
  struct PlaneCut {
    Vec3 point, normal;
    Bounds3 box;
    double area;
    std::size_t vertices;
  };
  const std::vector<PlaneCut> cuts{
      {{0, 0, 0.25}, {0, 0, 1}, unit, 1, 4},                            // a square
      {{0.5, 0.5, 0.5}, {1, 1, 1}, unit, 3 * std::sqrt(3.0) / 4, 6},    // a regular hexagon
      {{0.5, 0, 0}, {1, 1, 1}, unit, std::sqrt(3.0) / 8, 3},            // a corner cut off
      {{1, 0, 0}, {1, 1, 0}, unit, std::sqrt(2.0), 4},                  // the diagonal rectangle
      {{0, 0, 0}, {0, 0, -1}, unit, 1, 4},                              // along a face
      {{0, 0, -2}, {0, 0, 1}, Bounds3{{-1, 0, -3}, {2, 1, -1}}, 3, 4},  // another box
      {{0.5, 0, 0}, {1, 2, 0.5}, kClipBox, -1, 0},  // a slanted cut: containment and winding only
  };
  for (const PlaneCut& cut : cuts) {
    SCOPED_TRACE(::testing::Message() << "normal " << cut.normal << " through " << cut.point);
    const Plane plane(cut.point, cut.normal);
    const TriangleMesh mesh = tessellated(plane, 16, cut.box);
    if (cut.area > 0) {
      EXPECT_NEAR(total_area(mesh), cut.area, 1e-14);
      EXPECT_EQ(mesh.positions.size(), cut.vertices);
      EXPECT_EQ(mesh.triangles.size(), cut.vertices - 2);
    }
    for (const Vec3& p : mesh.positions) EXPECT_TRUE(cut.box.contains(p)) << p;
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
      EXPECT_GT(dot(mesh.face_cross(t), plane.normal()), 0);
  }
}

TEST(Tessellation, PlaneMissingOrOnlyTouchingTheBoxGivesNothing) {
  const Bounds3 unit{{0, 0, 0}, {1, 1, 1}};
  EXPECT_TRUE(tessellated(Plane({0, 0, 2}, {0, 0, 1}), 16, unit).triangles.empty());       // misses
  EXPECT_TRUE(tessellated(Plane({0, 0, 0}, {1, 1, 0}), 16, unit).triangles.empty());       // an edge
  EXPECT_TRUE(tessellated(Plane({0, 0, 0}, {1, 1, 1}), 16, unit).triangles.empty());       // a corner
  EXPECT_TRUE(tessellated(Plane({0, 0, 0}, {0, 0, 1}), 16, Bounds3{}).triangles.empty());  // empty box
  const Bounds3 infinite{{-kInfinity, -kInfinity, -kInfinity}, {kInfinity, kInfinity, kInfinity}};
  const TriangleMesh nothing = tessellated(Plane({0, 0, 0}, {0, 0, 1}), 16, infinite);
  EXPECT_TRUE(nothing.triangles.empty());
  EXPECT_TRUE(nothing.positions.empty());
}

TEST(Tessellation, TransformedPlaneIsCutByTheWorldBox) {
  // The plane x = 1/√2 turned 45° about z is x + y = 1; in [-1, 1]³ that is a rectangle
  // √2 × 2. The object-space bounds of the box would give twice as much.
  const TransformedShape plane(std::make_unique<Plane>(Vec3{1 / std::sqrt(2.0), 0, 0}, Vec3{1, 0, 0}),
                               Transform::rotate(45, {0, 0, 1}));
  const Bounds3 box{{-1, -1, -1}, {1, 1, 1}};
  const TriangleMesh mesh = tessellated(plane, 16, box);
  EXPECT_NEAR(total_area(mesh), 2 * std::sqrt(2.0), 1e-13);
  for (const Vec3& p : mesh.positions) {
    EXPECT_TRUE(box.contains(p)) << p;
    EXPECT_NEAR(p.x + p.y, 1, 1e-14) << p;
  }
  // One piece without cracks: every boundary edge lies on a face of the box.
  for (const auto& [from, to] : boundary_edges(mesh)) {
    const Vec3 middle = (from + to) * 0.5;
    bool on_face = false;
    for (int axis = 0; axis < 3; ++axis) on_face |= std::fabs(std::fabs(middle[axis]) - 1) < 1e-14;
    EXPECT_TRUE(on_face) << from << " to " << to;
  }
}

TEST(Tessellation, MirroringTransformKeepsTheWindingOutward) {
  const Vec3 center{0.3, 0, 0};
  const Transform mirror = Transform::scale({-2, 1, 1});
  const TransformedShape sphere(std::make_unique<Sphere>(center, 1), mirror);
  const TriangleMesh mesh = tessellated(sphere, 16);
  const Vec3 world_center = mirror.point(center);
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
    EXPECT_GT(dot(mesh.face_cross(t), centroid(mesh, t) - world_center), 0) << t;
  // The same triangles as the untransformed sphere's, with areas scaled by the mirror.
  EXPECT_EQ(mesh.triangles.size(), tessellated(Sphere(center, 1), 16).triangles.size());
}

TEST(Tessellation, MeshTriangleCarriesItsCornerUvsButNotItsNormals) {
  const auto source = two_triangle_mesh();
  const TriangleMesh mesh = tessellated(MeshTriangle(source, 1), 8);
  ASSERT_EQ(mesh.triangles.size(), 1u);
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(corner(mesh, 0, k), source->positions[source->triangles[1][k]]);
    EXPECT_EQ(mesh.corner_uvs[0][k].x, source->corner_uvs[1][k].x);
    EXPECT_EQ(mesh.corner_uvs[0][k].y, source->corner_uvs[1][k].y);
  }
  EXPECT_TRUE(mesh.corner_normals.empty());
  // Without corner uvs: the defaults a hit reports, (0,0), (1,0), (1,1).
  auto bare = std::make_shared<TriangleMesh>(*source);
  bare->corner_uvs.clear();
  const TriangleMesh bare_mesh = tessellated(MeshTriangle(bare, 0), 8);
  EXPECT_EQ(bare_mesh.corner_uvs[0][2].x, 1);
  EXPECT_EQ(bare_mesh.corner_uvs[0][2].y, 1);
  // A degenerate triangle gives nothing.
  bare->positions[3] = bare->positions[1];
  EXPECT_TRUE(tessellated(MeshTriangle(bare, 1), 8).triangles.empty());
}

TEST(Tessellation, AppendsAfterOtherTrianglesAndLeavesNormalsToTheCaller) {
  TriangleMesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  mesh.triangles = {{0, 1, 2}};
  TessellationSettings settings;
  settings.segments = 8;
  Sphere({5, 0, 0}, 1).tessellate(settings, mesh);
  Box({-3, -3, -3}, {-2, -2, -2}).tessellate(settings, mesh);
  mesh.validate();
  const TriangleMesh sphere_alone = tessellated(Sphere({5, 0, 0}, 1), 8);
  ASSERT_EQ(mesh.triangles.size(), 1 + sphere_alone.triangles.size() + 12);
  // The first triangle keeps its meaning: its default uvs are written out.
  EXPECT_EQ(mesh.corner_uvs[0][1].x, 1);
  EXPECT_EQ(mesh.corner_uvs[0][1].y, 0);
  // The sphere's triangles follow, indices offset by the three vertices before them.
  for (std::size_t t = 0; t < sphere_alone.triangles.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(mesh.triangles[1 + t][k], sphere_alone.triangles[t][k] + 3);
      EXPECT_EQ(mesh.corner_uvs[1 + t][k].x, sphere_alone.corner_uvs[t][k].x);
    }
  }
  // Corner normals are computed once every shape is in; a mesh that has them is refused.
  compute_corner_normals(mesh, 60);
  EXPECT_THROW(Sphere({0, 0, 0}, 1).tessellate(settings, mesh), std::logic_error);
}

}  // namespace
}  // namespace candela
