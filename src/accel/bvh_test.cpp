#include "accel/bvh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <tuple>
#include <vector>

#include "accel/bvh_builder.h"
#include "accel/primitive_list.h"
#include "geometry/plane.h"
#include "geometry/quad.h"
#include "geometry/sphere.h"
#include "geometry/transformed_shape.h"
#include "geometry/triangle_mesh.h"
#include "math/constants.h"
#include "math/pcg32.h"
#include "math/transform.h"

namespace candela {
namespace {

// Shapes and the primitives that point at them.
struct TestScene {
  std::vector<std::unique_ptr<Shape>> shapes;
  std::vector<Primitive> primitives;

  void add(std::unique_ptr<Shape> shape) {
    primitives.push_back({shape.get(), 0, static_cast<uint32_t>(shapes.size())});
    shapes.push_back(std::move(shape));
  }
  void add_mesh(const std::shared_ptr<const TriangleMesh>& mesh) {
    for (auto& triangle : make_triangles(mesh)) add(std::move(triangle));
  }
  Bounds3 bounds() const {
    Bounds3 b;
    for (const auto& shape : shapes) {
      const Bounds3 s = shape->bounds();
      if (s.is_finite()) b.extend(s);
    }
    return b;
  }
};

double uniform(Pcg32& rng, double lo, double hi) {
  return lo + (hi - lo) * rng.next_double();
}

Vec3 random_in(Pcg32& rng, const Bounds3& b) {
  return {uniform(rng, b.lower.x, b.upper.x), uniform(rng, b.lower.y, b.upper.y),
          uniform(rng, b.lower.z, b.upper.z)};
}

Vec3 random_direction(Pcg32& rng) {
  while (true) {
    const Vec3 d{uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1)};
    const double l2 = length_squared(d);
    if (l2 > 1e-4 && l2 <= 1) return d / std::sqrt(l2);
  }
}

// p with each coordinate rounded to float. Out of line: GCC 12.2's SLP vectoriser at -O2 drops
// the x and y conversions of `p = {float(p.x), float(p.y), float(p.z)}` (a double -> float ->
// double round trip of two adjacent doubles is folded to nothing; z, done alone, survives).
[[gnu::noinline]] double rounded_to_float(double v) {
  return static_cast<float>(v);
}
Vec3 rounded_to_float(const Vec3& p) {
  return {rounded_to_float(p.x), rounded_to_float(p.y), rounded_to_float(p.z)};
}

Bounds3 grown(const Bounds3& b, double factor) {
  const Vec3 margin = b.diagonal() * factor + Vec3{1e-3, 1e-3, 1e-3};
  return {b.lower - margin, b.upper + margin};
}

// A mix of rays: from anywhere around and inside the scene towards random points of it, random
// directions, and directions with components of +0 or -0.
std::vector<Ray> random_rays(Pcg32& rng, const Bounds3& scene, int count) {
  std::vector<Ray> rays;
  const Bounds3 around = grown(scene, 0.5);
  for (int i = 0; i < count; ++i) {
    Ray ray;
    ray.origin = random_in(rng, i % 3 == 0 ? scene : around);
    switch (i % 4) {
      case 0:
        ray.direction = random_direction(rng);
        break;
      case 1:
      case 2: {
        const Vec3 d = random_in(rng, scene) - ray.origin;
        ray.direction = length_squared(d) > 0 ? normalize(d) : Vec3{0, 0, 1};
        break;
      }
      default: {
        // Axis-aligned or in a coordinate plane, with signed zeros.
        Vec3 d = random_direction(rng);
        const int zeros = 1 + static_cast<int>(rng.next_uint() % 2);
        const int first = static_cast<int>(rng.next_uint() % 3);
        for (int k = 0; k < zeros; ++k) d[(first + k) % 3] = (rng.next_uint() & 1) ? 0.0 : -0.0;
        ray.direction = normalize(d);
        break;
      }
    }
    if (i % 7 == 0) ray.t_min = 1e-3;
    if (i % 11 == 0) ray.t_max = uniform(rng, 0.1, 2) * length(scene.diagonal());
    rays.push_back(ray);
  }
  return rays;
}

void expect_same_vec(const Vec3& a, const Vec3& b, const char* what) {
  EXPECT_TRUE(a == b || (std::isnan(a.x) && std::isnan(b.x))) << what << ": " << a << " vs " << b;
}

struct Agreement {
  int hits = 0;
  int occluded = 0;
};

// Every ray gets the same nearest hit (index, t, normals, uv bit for bit) and the same
// occlusion answers from the BVH as from the list.
Agreement expect_same_as_list(const TestScene& scene, const std::vector<Ray>& rays,
                              const BvhSettings& settings = {}) {
  PrimitiveList list;
  list.build(scene.primitives);
  Bvh bvh(settings);
  bvh.build(scene.primitives);
  Agreement agreement;
  int failures = 0;
  for (std::size_t i = 0; i < rays.size() && failures < 10; ++i) {
    const Ray& ray = rays[i];
    Intersection expected, actual;
    const bool expected_hit = list.intersect(ray, expected);
    const bool actual_hit = bvh.intersect(ray, actual);
    EXPECT_EQ(actual_hit, expected_hit)
        << "ray " << i << " origin " << ray.origin << " direction " << ray.direction;
    if (actual_hit != expected_hit) {
      ++failures;
      continue;
    }
    if (expected_hit) {
      ++agreement.hits;
      EXPECT_EQ(actual.primitive, expected.primitive) << "ray " << i;
      EXPECT_EQ(actual.surface.t, expected.surface.t) << "ray " << i;
      expect_same_vec(actual.surface.position, expected.surface.position, "position");
      expect_same_vec(actual.surface.geometric_normal, expected.surface.geometric_normal, "normal");
      expect_same_vec(actual.surface.shading_normal, expected.surface.shading_normal, "shading");
      EXPECT_EQ(actual.surface.uv.x, expected.surface.uv.x);
      EXPECT_EQ(actual.surface.uv.y, expected.surface.uv.y);
      if (actual.primitive != expected.primitive || actual.surface.t != expected.surface.t) ++failures;
    }
    // Occlusion over the whole ray and over a segment that ends before or at the nearest hit.
    EXPECT_EQ(bvh.occluded(ray), list.occluded(ray)) << "ray " << i;
    if (list.occluded(ray)) ++agreement.occluded;
    if (expected_hit) {
      Ray segment = ray;
      for (double t_max :
           {expected.surface.t, std::nextafter(expected.surface.t, kInfinity), expected.surface.t * 0.5}) {
        segment.t_max = t_max;
        EXPECT_EQ(bvh.occluded(segment), list.occluded(segment)) << "ray " << i << " t_max " << t_max;
      }
    }
  }
  return agreement;
}

std::shared_ptr<TriangleMesh> random_triangles(Pcg32& rng, int count, double extent, double size) {
  auto mesh = std::make_shared<TriangleMesh>();
  const Bounds3 box{{-extent, -extent, -extent}, {extent, extent, extent}};
  for (int i = 0; i < count; ++i) {
    const Vec3 center = random_in(rng, box);
    const auto first = static_cast<uint32_t>(mesh->positions.size());
    for (int k = 0; k < 3; ++k)
      mesh->positions.push_back(
          center + Vec3{uniform(rng, -size, size), uniform(rng, -size, size), uniform(rng, -size, size)});
    mesh->triangles.push_back({first, first + 1, first + 2});
  }
  return mesh;
}

// A latitude-longitude sphere with shared vertices (one vertex per pole, so the pole cells give
// degenerate triangles, which make_triangles leaves out): 2 · rings · segments - 2 · segments
// triangles, with smooth corner normals.
std::shared_ptr<TriangleMesh> tessellated_sphere(int rings, int segments, double radius) {
  auto mesh = std::make_shared<TriangleMesh>();
  const auto vertex = [&](int ring, int segment) -> uint32_t {
    if (ring == 0) return 0;
    if (ring == rings) return 1;
    return static_cast<uint32_t>(2 + (ring - 1) * segments + segment % segments);
  };
  mesh->positions.push_back({0, 0, radius});
  mesh->positions.push_back({0, 0, -radius});
  for (int ring = 1; ring < rings; ++ring) {
    const double theta = kPi * ring / rings;
    for (int segment = 0; segment < segments; ++segment) {
      const double phi = 2 * kPi * segment / segments;
      mesh->positions.push_back({radius * std::sin(theta) * std::cos(phi),
                                 radius * std::sin(theta) * std::sin(phi), radius * std::cos(theta)});
    }
  }
  for (int ring = 0; ring < rings; ++ring) {
    for (int segment = 0; segment < segments; ++segment) {
      const uint32_t a = vertex(ring, segment), b = vertex(ring + 1, segment);
      const uint32_t c = vertex(ring + 1, segment + 1), d = vertex(ring, segment + 1);
      mesh->triangles.push_back({a, b, c});
      mesh->triangles.push_back({a, c, d});
    }
  }
  compute_corner_normals(*mesh, 180);
  return mesh;
}

// The traversal's instruction sets this CPU runs (SSE2 at least: it is part of x86-64).
std::vector<BvhIsa> instruction_sets_of_this_cpu() {
  std::vector<BvhIsa> sets;
  for (BvhIsa isa : {BvhIsa::sse, BvhIsa::avx2, BvhIsa::avx512})
    if (static_cast<int>(isa) <= static_cast<int>(widest_bvh_isa())) sets.push_back(isa);
  return sets;
}

BvhSettings with_isa(BvhIsa isa) {
  BvhSettings settings;
  settings.isa = isa;
  return settings;
}

TEST(Bvh, NameAndEmptyScene) {
  Bvh bvh;
  EXPECT_EQ(bvh.name(), "bvh");
  bvh.build({});
  Intersection intersection;
  const Ray ray{{0, 0, 0}, {0, 0, 1}};
  EXPECT_FALSE(bvh.intersect(ray, intersection));
  EXPECT_FALSE(bvh.occluded(ray));
  const AcceleratorReport report = bvh.report();
  ASSERT_FALSE(report.figures.empty());
  EXPECT_EQ(report.figures[0].first, "nodes");
  EXPECT_EQ(report.figures[0].second, 0);
}

TEST(Bvh, RejectsInvalidSettings) {
  BvhSettings settings;
  settings.max_leaf_primitives = -1;  // 0 is automatic
  EXPECT_THROW(Bvh{settings}, std::invalid_argument);
  settings = {};
  settings.bins = 1;
  EXPECT_THROW(Bvh{settings}, std::invalid_argument);
}

TEST(Bvh, RandomSpheresMatchList) {
  Pcg32 rng(7, 1);
  TestScene scene;
  for (int i = 0; i < 400; ++i)
    scene.add(
        std::make_unique<Sphere>(random_in(rng, {{-10, -10, -10}, {10, 10, 10}}), uniform(rng, 0.1, 1.0)));
  const Agreement agreement = expect_same_as_list(scene, random_rays(rng, scene.bounds(), 4000));
  EXPECT_GT(agreement.hits, 1000);
}

TEST(Bvh, RandomTrianglesMatchList) {
  Pcg32 rng(11, 2);
  TestScene scene;
  scene.add_mesh(random_triangles(rng, 2000, 10, 1.5));
  const Agreement agreement = expect_same_as_list(scene, random_rays(rng, scene.bounds(), 4000));
  EXPECT_GT(agreement.hits, 1000);
}

TEST(Bvh, OtherSettingsMatchList) {
  Pcg32 rng(13, 3);
  TestScene scene;
  scene.add_mesh(random_triangles(rng, 800, 10, 1.0));
  for (int i = 0; i < 100; ++i)
    scene.add(std::make_unique<Sphere>(random_in(rng, {{-10, -10, -10}, {10, 10, 10}}), 0.5));
  const std::vector<Ray> rays = random_rays(rng, scene.bounds(), 1500);
  for (const auto& [max_leaf, bins] :
       {std::pair{1, 2}, std::pair{2, 64}, std::pair{8, 7}, std::pair{32, 16}}) {
    SCOPED_TRACE(::testing::Message() << "max leaf " << max_leaf << ", bins " << bins);
    BvhSettings settings;
    settings.max_leaf_primitives = max_leaf;
    settings.bins = bins;
    EXPECT_GT(expect_same_as_list(scene, rays, settings).hits, 300);
  }
}

// Coincident primitives hit at exactly the same t: the lowest index must win, even when the
// copies end up in different leaves (more copies than a leaf holds).
TEST(Bvh, DuplicatesKeepTheLowestIndex) {
  Pcg32 rng(17, 4);
  auto base = random_triangles(rng, 30, 5, 2.0);
  auto mesh = std::make_shared<TriangleMesh>(*base);
  // Each triangle 40 times, interleaved, plus copies with rotated corners (same plane, other
  // corner order: the same t is not guaranteed then, but whichever wins must agree).
  mesh->triangles.clear();
  for (int copy = 0; copy < 40; ++copy)
    for (const auto& tri : base->triangles) mesh->triangles.push_back(tri);
  for (const auto& tri : base->triangles) mesh->triangles.push_back({tri[1], tri[2], tri[0]});
  TestScene scene;
  scene.add_mesh(mesh);
  for (int i = 0; i < 20; ++i) {
    const Vec3 center = random_in(rng, {{-5, -5, -5}, {5, 5, 5}});
    for (int copy = 0; copy < 25; ++copy) scene.add(std::make_unique<Sphere>(center, 1.0));
  }
  std::vector<Ray> rays = random_rays(rng, scene.bounds(), 2000);
  // Rays aimed at triangle corners and edge midpoints (shared by copies).
  for (const auto& tri : base->triangles) {
    for (int k = 0; k < 3; ++k) {
      const Vec3 target = k == 0 ? base->positions[tri[0]]
                                 : (base->positions[tri[k]] + base->positions[tri[(k + 1) % 3]]) * 0.5;
      Ray ray;
      ray.origin = random_in(rng, {{-12, -12, -12}, {12, 12, 12}});
      ray.direction = normalize(target - ray.origin);
      rays.push_back(ray);
    }
  }
  const Agreement agreement = expect_same_as_list(scene, rays);
  EXPECT_GT(agreement.hits, 500);
}

TEST(Bvh, AllPrimitivesAtOnePoint) {
  Pcg32 rng(19, 5);
  TestScene scene;
  const Vec3 point{1, 2, 3};
  for (int i = 0; i < 100; ++i) scene.add(std::make_unique<Sphere>(point, uniform(rng, 0.5, 1.5)));
  for (int i = 0; i < 60; ++i) scene.add(std::make_unique<Sphere>(point, 1.0));
  // Triangles whose centroids all coincide with the point.
  auto mesh = std::make_shared<TriangleMesh>();
  for (int i = 0; i < 100; ++i) {
    const Vec3 a = random_direction(rng), b = random_direction(rng);
    const auto first = static_cast<uint32_t>(mesh->positions.size());
    mesh->positions.push_back(point + a);
    mesh->positions.push_back(point + b);
    mesh->positions.push_back(point - a - b);
    mesh->triangles.push_back({first, first + 1, first + 2});
  }
  scene.add_mesh(mesh);
  const Agreement agreement = expect_same_as_list(scene, random_rays(rng, scene.bounds(), 3000));
  EXPECT_GT(agreement.hits, 500);
}

TEST(Bvh, PlanesAndBoundedPrimitives) {
  Pcg32 rng(23, 6);
  TestScene scene;
  scene.add(std::make_unique<Plane>(Vec3{0, -8, 0}, Vec3{0, 1, 0}));
  scene.add_mesh(random_triangles(rng, 500, 8, 1.0));
  scene.add(std::make_unique<Plane>(Vec3{0, 0, 9}, normalize(Vec3{0.1, 0.2, -1})));
  for (int i = 0; i < 200; ++i)
    scene.add(std::make_unique<Sphere>(random_in(rng, {{-8, -8, -8}, {8, 8, 8}}), 0.4));
  scene.add(std::make_unique<Plane>(Vec3{0, -8, 0}, Vec3{0, 1, 0}));  // a duplicate plane
  // A transformed plane: its t_max test is in its own (scaled) coordinates, so a second intersect
  // under next_up(t) may refuse the hit its first found.
  scene.add(
      std::make_unique<TransformedShape>(std::make_unique<Plane>(Vec3{0, 0, 0}, Vec3{1, 0, 0.2}),
                                         Transform::translate({8.5, 0, 0}) * Transform::scale({3, 3, 3})));
  const Agreement agreement = expect_same_as_list(scene, random_rays(rng, scene.bounds(), 3000));
  EXPECT_GT(agreement.hits, 1500);

  Bvh bvh;
  bvh.build(scene.primitives);
  for (const auto& [name, value] : bvh.report().figures)
    if (name == "unbounded primitives") {
      EXPECT_EQ(value, 4);
    }
}

// A plane's hit, filled at the end of the traversal, goes into a fresh hit: an Intersection
// reused after a smooth mesh's hit keeps none of that mesh's interpolated-normal flag and
// terminator lifts.
TEST(Bvh, APlaneHitInAReusedIntersectionIsFreshlyFilled) {
  TestScene scene;
  auto mesh = tessellated_sphere(12, 24, 1.0);
  mesh->corner_normals.clear();
  for (const auto& triangle : mesh->triangles)
    mesh->corner_normals.push_back({normalize(mesh->positions[triangle[0]]),
                                    normalize(mesh->positions[triangle[1]]),
                                    normalize(mesh->positions[triangle[2]])});
  scene.add_mesh(mesh);
  scene.add(std::make_unique<Plane>(Vec3{0, -3, 0}, Vec3{0, 1, 0}));
  Bvh bvh;
  bvh.build(scene.primitives);
  Intersection reused;
  int lifted = 0;
  for (int i = 0; i < 64; ++i) {
    const double angle = 0.1 * i;
    Ray to_mesh;  // grazing the smooth sphere, where the lifts are largest
    to_mesh.origin = {4 * std::cos(angle), 0.95 * std::sin(3 * angle), 4 * std::sin(angle)};
    to_mesh.direction = normalize(Vec3{0, 0.1, 0} - to_mesh.origin);
    ASSERT_TRUE(bvh.intersect(to_mesh, reused));
    ASSERT_TRUE(reused.surface.interpolated_normal);
    if (length(reused.surface.terminator_lift_outside) + length(reused.surface.terminator_lift_inside) > 0)
      ++lifted;
    Ray to_plane;
    to_plane.origin = {5 + std::cos(angle), 0, std::sin(angle)};
    to_plane.direction = normalize(Vec3{0.1 * std::sin(angle), -1, 0.2});
    Intersection fresh;
    ASSERT_TRUE(bvh.intersect(to_plane, fresh));
    ASSERT_TRUE(bvh.intersect(to_plane, reused));
    EXPECT_EQ(reused.primitive, fresh.primitive);
    EXPECT_EQ(reused.surface.t, fresh.surface.t);
    EXPECT_FALSE(reused.surface.interpolated_normal) << i;
    EXPECT_EQ(reused.surface.terminator_lift_outside, Vec3{}) << i;
    EXPECT_EQ(reused.surface.terminator_lift_inside, Vec3{}) << i;
  }
  EXPECT_GT(lifted, 10);
}

TEST(Bvh, OnlyPlanes) {
  TestScene scene;
  scene.add(std::make_unique<Plane>(Vec3{0, 0, 0}, Vec3{0, 0, 1}));
  scene.add(std::make_unique<Plane>(Vec3{0, 0, 1}, Vec3{0, 0, 1}));
  Bvh bvh;
  bvh.build(scene.primitives);
  Intersection intersection;
  ASSERT_TRUE(bvh.intersect(Ray{{0, 0, 5}, {0, 0, -1}}, intersection));
  EXPECT_EQ(intersection.primitive, 1u);
  EXPECT_EQ(intersection.surface.t, 4.0);
  EXPECT_TRUE(bvh.occluded(Ray{{0, 0, 5}, {0, 0, -1}}));
  EXPECT_FALSE(bvh.occluded(Ray{{0, 0, 5}, {1, 0, 0}}));
}

// Axis-aligned rays running exactly in the planes of axis-aligned boxes and triangle edges:
// the slab test sees 0 · inf.
TEST(Bvh, AxisAlignedRaysInBoxPlanes) {
  auto mesh = std::make_shared<TriangleMesh>();
  for (int i = 0; i < 6; ++i) {
    for (int j = 0; j < 6; ++j) {
      for (int k = 0; k < 6; ++k) {
        const auto first = static_cast<uint32_t>(mesh->positions.size());
        const Vec3 p{double(i), double(j), double(k)};
        mesh->positions.push_back(p);
        mesh->positions.push_back(p + Vec3{1, 0, 0});
        mesh->positions.push_back(p + Vec3{0, 1, 0});
        mesh->positions.push_back(p + Vec3{0, 0, 1});
        mesh->triangles.push_back({first, first + 1, first + 2});  // z = k
        mesh->triangles.push_back({first, first + 3, first + 1});  // y = j
        mesh->triangles.push_back({first, first + 2, first + 3});  // x = i
      }
    }
  }
  TestScene scene;
  scene.add_mesh(mesh);
  std::vector<Ray> rays;
  for (int axis = 0; axis < 3; ++axis) {
    for (double sign : {1.0, -1.0}) {
      for (double a : {0.0, 0.25, 1.0, 2.5, 3.0, 6.0}) {
        for (double b : {0.0, 0.5, 1.0, 2.0, 4.75, 6.0}) {
          Ray ray;
          ray.origin[axis] = sign > 0 ? -1.0 : 8.0;
          ray.origin[(axis + 1) % 3] = a;
          ray.origin[(axis + 2) % 3] = b;
          ray.direction[axis] = sign;
          ray.direction[(axis + 1) % 3] = sign > 0 ? 0.0 : -0.0;
          ray.direction[(axis + 2) % 3] = sign > 0 ? -0.0 : 0.0;
          rays.push_back(ray);
          ray.origin[axis] = 3.0;  // starting inside, on a triangle's plane
          rays.push_back(ray);
        }
      }
    }
  }
  const Agreement agreement = expect_same_as_list(scene, rays);
  EXPECT_GT(agreement.hits, 100);
}

TEST(Bvh, LargeTessellatedSphereMatchesList) {
  TestScene scene;
  scene.add_mesh(tessellated_sphere(112, 224, 2.0));
  ASSERT_GT(scene.primitives.size(), 49000u);
  Pcg32 rng(29, 7);
  std::vector<Ray> rays = random_rays(rng, scene.bounds(), 600);
  // Rays towards mesh vertices (shared by up to six triangles: ties at equal t).
  const auto& positions = static_cast<const MeshTriangle*>(scene.primitives[0].shape)->mesh().positions;
  for (int i = 0; i < 200; ++i) {
    const Vec3 target = positions[rng.next_uint() % positions.size()];
    Ray ray;
    ray.origin = random_in(rng, {{-6, -6, -6}, {6, 6, 6}});
    ray.direction = normalize(target - ray.origin);
    rays.push_back(ray);
  }
  const Agreement agreement = expect_same_as_list(scene, rays);
  EXPECT_GT(agreement.hits, 400);

  Bvh bvh;
  bvh.build(scene.primitives);
  const AcceleratorReport report = bvh.report();
  double nodes = 0, leaves = 0, depth = 0, sah = 0, per_leaf = 0;
  for (const auto& [name, value] : report.figures) {
    if (name == "nodes") nodes = value;
    if (name == "leaves") leaves = value;
    if (name == "depth") depth = value;
    if (name == "SAH cost") sah = value;
    if (name == "primitives per leaf") per_leaf = value;
  }
  const double primitives = static_cast<double>(scene.primitives.size());
  EXPECT_GE(leaves, primitives / 16);
  EXPECT_EQ(nodes, 2 * leaves - 1);
  EXPECT_GT(depth, std::log2(primitives / 16));
  EXPECT_LT(depth, 64);
  EXPECT_GT(sah, 1);
  EXPECT_LT(sah, 200);
  EXPECT_NEAR(per_leaf * leaves, primitives, 1e-6 * primitives);
  EXPECT_GE(per_leaf, 1);
  EXPECT_LE(per_leaf, 16);
  EXPECT_GT(report.bytes, primitives * 72);
}

TEST(Bvh, RaysFromInsideTheMesh) {
  TestScene scene;
  scene.add_mesh(tessellated_sphere(40, 80, 1.0));
  Pcg32 rng(31, 8);
  std::vector<Ray> rays;
  for (int i = 0; i < 1000; ++i) {
    Ray ray;
    ray.origin = random_in(rng, {{-0.5, -0.5, -0.5}, {0.5, 0.5, 0.5}});
    ray.direction = random_direction(rng);
    rays.push_back(ray);
  }
  const Agreement agreement = expect_same_as_list(scene, rays);
  EXPECT_EQ(agreement.hits, 1000);  // closed and watertight: every ray leaves through it
}

// Fewer primitives than a leaf holds: the tree is a single leaf.
TEST(Bvh, SingleLeafTree) {
  Pcg32 rng(37, 9);
  TestScene scene;
  scene.add(std::make_unique<Sphere>(Vec3{0, 0, 0}, 1.0));
  scene.add_mesh(random_triangles(rng, 2, 1, 1.0));
  Bvh bvh;
  bvh.build(scene.primitives);
  for (const auto& [name, value] : bvh.report().figures) {
    if (name == "nodes" || name == "leaves" || name == "depth") {
      EXPECT_EQ(value, 1) << name;
    }
  }
  EXPECT_GT(expect_same_as_list(scene, random_rays(rng, scene.bounds(), 1000)).hits, 200);
}

TEST(Bvh, DegenerateTrianglesNeverHit) {
  auto mesh = std::make_shared<TriangleMesh>();
  mesh->positions = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 0}};
  mesh->triangles = {{0, 1, 2}, {0, 1, 3}};
  TestScene scene;
  scene.add(std::make_unique<MeshTriangle>(mesh, 0));  // collinear: kept by the constructor
  scene.add(std::make_unique<MeshTriangle>(mesh, 1));
  Bvh bvh;
  bvh.build(scene.primitives);
  Intersection intersection;
  ASSERT_TRUE(bvh.intersect(Ray{{0.25, 0.25, 1}, {0, 0, -1}}, intersection));
  EXPECT_EQ(intersection.primitive, 1u);
  EXPECT_FALSE(bvh.intersect(Ray{{1.5, 0.0, 1}, {0, 0, -1}}, intersection));
}

// Tiny triangles far from the origin: the float boxes and the float triangle pre-test round at
// a scale far larger than the triangles, and must still never cull a hit.
TEST(Bvh, TinyTrianglesFarFromTheOrigin) {
  auto mesh = tessellated_sphere(48, 96, 1e-3);
  const Vec3 offset{3e4, -2e4, 1e4};
  for (Vec3& p : mesh->positions) p = p + offset;
  TestScene scene;
  scene.add_mesh(mesh);
  Pcg32 rng(41, 10);
  std::vector<Ray> rays = random_rays(rng, scene.bounds(), 1500);
  for (int i = 0; i < 1500; ++i) {  // towards vertices, from near and far
    const Vec3 target = mesh->positions[rng.next_uint() % mesh->positions.size()];
    Ray ray;
    ray.origin = offset + random_direction(rng) * (i % 2 ? 5e-3 : 50.0);
    ray.direction = normalize(target - ray.origin);
    rays.push_back(ray);
  }
  const Agreement agreement = expect_same_as_list(scene, rays);
  EXPECT_GT(agreement.hits, 1500);
}

// Rays outside the float test's proven range (tiny or huge components, huge origins, very
// negative t_min) and rays with a negative t_min: the BVH still answers as the list.
TEST(Bvh, RaysOutsideTheFloatRange) {
  Pcg32 rng(43, 11);
  TestScene scene;
  scene.add_mesh(random_triangles(rng, 400, 4, 1.0));
  scene.add(std::make_unique<Sphere>(Vec3{0, 0, 0}, 0.5));
  std::vector<Ray> rays;
  for (int i = 0; i < 400; ++i) {
    Ray ray;
    ray.origin = random_in(rng, {{-6, -6, -6}, {6, 6, 6}});
    Vec3 d = random_direction(rng);
    switch (i % 6) {
      case 0:
        d[i % 3] = 1e-35;
        break;  // a tiny component
      case 1:
        d[i % 3] = -1e-300;
        break;  // a double subnormal-ish one
      case 2:
        d = d * 1e35;
        break;  // huge direction
      case 3:
        ray.origin[i % 3] = 1e31;
        d[i % 3] = -1;
        break;  // huge origin
      case 4:
        ray.t_min = -1e31;
        break;  // very negative t_min
      default:
        ray.t_min = -uniform(rng, 0, 8);
        break;  // hits behind the origin count
    }
    ray.direction = d;
    rays.push_back(ray);
  }
  const Agreement agreement = expect_same_as_list(scene, rays);
  EXPECT_GT(agreement.hits, 50);
}

// Two meshes with smooth normals: the hit is filled through each triangle's own mesh.
TEST(Bvh, TwoMeshesFillTheirOwnNormals) {
  TestScene scene;
  scene.add_mesh(tessellated_sphere(20, 40, 1.0));
  auto second = tessellated_sphere(16, 32, 0.7);
  for (Vec3& p : second->positions) p = p + Vec3{1.5, 0.25, 0};
  scene.add_mesh(second);
  Pcg32 rng(47, 12);
  const Agreement agreement = expect_same_as_list(scene, random_rays(rng, scene.bounds(), 2000));
  EXPECT_GT(agreement.hits, 800);
}

// The traversal is compiled for SSE, AVX2 and AVX-512 and picked at run time; every
// instruction set this CPU has gives the list's answers, on double vertices (kept beside the
// packets) and on float vertices (the packets alone), with shapes mixed in.
TEST(Bvh, EveryInstructionSetOfThisCpuGivesTheListsAnswers) {
  Pcg32 rng(41, 10);
  TestScene doubles;
  doubles.add_mesh(random_triangles(rng, 1500, 10, 1.5));
  for (int i = 0; i < 60; ++i)
    doubles.add(std::make_unique<Sphere>(random_in(rng, {{-10, -10, -10}, {10, 10, 10}}), 0.5));
  auto floats = std::make_shared<TriangleMesh>(*tessellated_sphere(60, 120, 2.0));
  for (Vec3& p : floats->positions) p = rounded_to_float(p);
  TestScene float_scene;
  float_scene.add_mesh(floats);
  const std::vector<Ray> rays = random_rays(rng, doubles.bounds(), 1500);
  const std::vector<Ray> sphere_rays = random_rays(rng, float_scene.bounds(), 1500);
  const std::vector<BvhIsa> sets = instruction_sets_of_this_cpu();
  EXPECT_GE(sets.size(), 1u);  // SSE2 is part of x86-64
  for (BvhIsa isa : sets) {
    SCOPED_TRACE(std::string(kBvhIsaNames.name(isa)));
    EXPECT_GT(expect_same_as_list(doubles, rays, with_isa(isa)).hits, 300);
    EXPECT_GT(expect_same_as_list(float_scene, sphere_rays, with_isa(isa)).hits, 300);
  }
  EXPECT_NE(widest_bvh_isa(), BvhIsa::automatic);
}

// The any-hit traversal's float test of t_min (FloatShear::candidates<true>) rejects only lanes
// the exact test rejects too: shadow rays leaving a surface point (their own triangle at t ~ 0,
// rejected by t_min = 1e-4 of the scene, as in the benchmark's shadow set), and rays whose
// t_min lies just before or after their first hit (a sign slip would drop that hit), in every
// direction and for both windings, double and float vertices, each instruction set.
TEST(Bvh, ShadowRaysFromASurfaceAndTMinNearAHitGiveTheListsAnswers) {
  Pcg32 rng(43, 12);
  TestScene doubles;
  doubles.add_mesh(random_triangles(rng, 1200, 10, 1.5));
  auto floats = std::make_shared<TriangleMesh>(*tessellated_sphere(40, 80, 6.0));
  for (Vec3& p : floats->positions) p = rounded_to_float(p);
  doubles.add_mesh(floats);
  PrimitiveList list;
  list.build(doubles.primitives);
  const double diagonal = length(doubles.bounds().diagonal());
  std::vector<Ray> rays;
  int surface_rays = 0;
  for (const Ray& probe : random_rays(rng, doubles.bounds(), 1000)) {
    Intersection first;
    if (!list.intersect(probe, first)) continue;
    const double t = first.surface.t;
    for (double factor : {1 - 1e-7, 1 - 1e-3, 1 + 1e-7, 1 + 1e-3}) {
      Ray near_hit = probe;
      near_hit.t_min = t * factor;
      rays.push_back(near_hit);
    }
    // From the hit point towards a point light, and back along the ray.
    Ray shadow;
    shadow.origin = first.surface.position;
    const Vec3 light = random_in(rng, grown(doubles.bounds(), 0.3));
    shadow.direction = normalize(light - shadow.origin);
    shadow.t_min = 1e-4 * diagonal;
    shadow.t_max = std::max(shadow.t_min, length(light - shadow.origin) - 1e-4 * diagonal);
    rays.push_back(shadow);
    shadow.direction = -probe.direction;
    shadow.t_max = kInfinity;
    rays.push_back(shadow);
    surface_rays += 2;
  }
  ASSERT_GT(surface_rays, 600);
  for (BvhIsa isa : instruction_sets_of_this_cpu()) {
    SCOPED_TRACE(std::string(kBvhIsaNames.name(isa)));
    Bvh bvh(with_isa(isa));
    bvh.build(doubles.primitives);
    int occluded = 0, mismatches = 0;
    for (std::size_t i = 0; i < rays.size() && mismatches < 10; ++i) {
      const bool expected = list.occluded(rays[i]);
      occluded += expected;
      if (bvh.occluded(rays[i]) != expected) {
        ++mismatches;
        ADD_FAILURE() << "ray " << i << " origin " << rays[i].origin << " direction " << rays[i].direction
                      << " t_min " << rays[i].t_min << " expected occluded " << expected;
      }
    }
    // Both answers occur often: the rays with t_min just before their hit are all occluded.
    EXPECT_GT(occluded, static_cast<int>(rays.size()) / 4);
    EXPECT_LT(occluded, static_cast<int>(rays.size()) * 9 / 10);
  }
}

// The t_min pre-test at the ends of float's range (a review's counterexamples): one triangle
// hit just past t_min, seen from the origin along +z, where the float G underflows to −2^-149
// while its bound rounded to 0 (scale 2^-45), or overflows to −inf under a finite bound (scale
// 2^47). Both were rejected before the bound's 2^-126 floor and the finite-G condition; the
// exact test (and the list) says the ray is occluded.
TEST(Bvh, TheTMinPreTestKeepsAHitWhereItsFloatsUnderflowOrOverflow) {
  struct Case {
    double r, t_min, s, z0, z1, z2;
  };
  for (const Case& c : {Case{0x1p-45, 0x1p-50, 0x1p-60, -1.625, 1.375, 0.375},
                        Case{0x1p47, 0x1p40, 0x1p33, -1.5, 0.875, 0.875}}) {
    auto mesh = std::make_shared<TriangleMesh>();
    mesh->positions = {{-c.r, -c.r, c.t_min + c.z0 * c.s},
                       {0, 2 * c.r, c.t_min + c.z1 * c.s},
                       {c.r, -c.r, c.t_min + c.z2 * c.s}};
    mesh->triangles = {{0, 1, 2}};
    TestScene scene;
    scene.add_mesh(mesh);
    Ray ray;
    ray.origin = {0, 0, 0};
    ray.direction = {0, 0, 1};
    ray.t_min = c.t_min;
    PrimitiveList list;
    list.build(scene.primitives);
    ASSERT_TRUE(list.occluded(ray)) << "scale " << c.r;
    for (BvhIsa isa : instruction_sets_of_this_cpu()) {
      Bvh bvh(with_isa(isa));
      bvh.build(scene.primitives);
      EXPECT_TRUE(bvh.occluded(ray)) << "scale " << c.r << ", " << kBvhIsaNames.name(isa);
    }
  }
}

TEST(Bvh, AnInstructionSetTheCpuLacksIsRefused) {
  BvhSettings settings;
  settings.isa = BvhIsa::avx512;
  if (widest_bvh_isa() == BvhIsa::avx512) {
    EXPECT_NO_THROW(Bvh{settings});
  } else {
    EXPECT_THROW(Bvh{settings}, std::invalid_argument);
  }
  settings.isa = BvhIsa::sse;
  EXPECT_NO_THROW(Bvh{settings});
}

// Float vertices (the benchmark's meshes, Embree's input) are stored once, in the packets; a
// mesh with one vertex that is not a float keeps the double vertices beside them. Both are
// exact (the test above); this checks the memory each takes.
TEST(Bvh, FloatVerticesAreStoredOnlyInThePackets) {
  auto mesh = std::make_shared<TriangleMesh>(*tessellated_sphere(40, 80, 1.0));
  for (Vec3& p : mesh->positions) p = rounded_to_float(p);
  const auto bytes_per_triangle = [](const std::shared_ptr<TriangleMesh>& m) {
    TestScene scene;
    scene.add_mesh(m);
    Bvh bvh;
    bvh.build(scene.primitives);
    for (const auto& [name, value] : bvh.report().figures)
      if (name == "bytes per triangle") return value;
    return 0.0;
  };
  const double floats = bytes_per_triangle(mesh);
  mesh->positions[5].x += 1e-12;  // no longer a float
  const double doubles = bytes_per_triangle(mesh);
  // A packet is 176 bytes for up to four triangles (44 a triangle when full), plus the nodes.
  EXPECT_GT(floats, 44);
  EXPECT_LT(floats, 100);
  // The double vertices add 72 bytes a lane.
  EXPECT_GT(doubles, floats + 72);
}

// The SAH counts a leaf of n references as ceil(n / block_size) tests (a packet of four
// triangles is one float pre-test): a lone leaf of three costs one test, not three, and a
// triangle soup built with blocks of four gets fewer, fuller leaves.
TEST(BvhBuilder, BlockSizeCountsLeavesInPackets) {
  const std::vector<Bounds3> three = {{{0, 0, 0}, {1, 1, 1}}, {{2, 0, 0}, {3, 1, 1}}, {{4, 0, 0}, {5, 1, 1}}};
  BvhBuildSettings settings;
  settings.max_leaf_primitives = 4;
  EXPECT_DOUBLE_EQ(build_bvh(three, settings).sah_cost, 3 * settings.intersection_cost);
  settings.block_size = 4;
  EXPECT_DOUBLE_EQ(build_bvh(three, settings).sah_cost, settings.intersection_cost);

  Pcg32 rng(43, 11);
  std::vector<Bounds3> soup;
  for (int i = 0; i < 4000; ++i) {
    const Vec3 p = random_in(rng, {{-10, -10, -10}, {10, 10, 10}});
    soup.push_back({p, p + Vec3{0.3, 0.3, 0.3}});
  }
  BvhBuildSettings single;
  single.max_leaf_primitives = 1;
  BvhBuildSettings packets = single;
  packets.block_size = 4;
  const BvhBuildResult by_one = build_bvh(soup, single), by_four = build_bvh(soup, packets);
  EXPECT_LT(by_four.leaves * 2, by_one.leaves);
  EXPECT_LT(by_four.depth, by_one.depth);
  for (const BvhBuildResult* tree : {&by_one, &by_four}) {
    std::vector<int> seen(soup.size(), 0);
    for (const BvhBuildNode& node : tree->nodes) {
      EXPECT_LE(node.count, 16u);
      for (uint32_t k = node.index; node.count > 0 && k < node.index + node.count; ++k)
        ++seen[tree->order[k]];
    }
    EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), static_cast<std::ptrdiff_t>(soup.size()));
  }
}

// Primitives that share one centroid cannot be separated by any split (they are
// halved into overlapping leaves of at most 16); the build says how many, and warns past 256.
TEST(Bvh, ManyPrimitivesWithOneCentroidAreCountedAndWarnedAbout) {
  // Distinct triangles whose boxes [-x, x] × [-y, y] × [-z, z] all have their centre at 0.
  auto mesh = std::make_shared<TriangleMesh>();
  for (int i = 0; i < 2000; ++i) {
    const double x = 1 + i / 1024.0, y = 1 + i / 2048.0, z = 0.5 + i / 4096.0;
    const auto first = static_cast<uint32_t>(mesh->positions.size());
    mesh->positions.insert(mesh->positions.end(), {{x, y, 0}, {-x, 0, z}, {0, -y, -z}});
    mesh->triangles.push_back({first, first + 1, first + 2});
  }
  TestScene scene;
  scene.add_mesh(mesh);
  Bvh bvh;
  bvh.build(scene.primitives);
  const AcceleratorReport report = bvh.report();
  double group = 0;
  for (const auto& [name, value] : report.figures)
    if (name == "largest coincident group") group = value;
  EXPECT_EQ(group, 2000);
  ASSERT_EQ(report.warnings.size(), 1u);
  EXPECT_NE(report.warnings[0].find("share one centroid"), std::string::npos);
  Pcg32 rng(47, 12);
  EXPECT_GT(expect_same_as_list(scene, random_rays(rng, {{-3, -3, -3}, {3, 3, 3}}, 300)).hits, 20);

  TestScene sphere;
  sphere.add_mesh(tessellated_sphere(30, 60, 1.0));
  Bvh plain;
  plain.build(sphere.primitives);
  EXPECT_TRUE(plain.report().warnings.empty());
}

// bvh-fast: float Möller–Trumbore leaves, outside the exact contract. Against the
// list: where both hit, the distance agrees to float's precision (any primitive: a neighbour
// across an edge is at the same distance); the nearest primitive, hit or miss and occlusion agree
// but for rays grazing an edge (a few in a thousand at most; none of these scenes' counts is
// near the bound); for every instruction set.
struct FastAgreement {
  int rays = 0, hits = 0, other_primitive = 0, hit_or_miss = 0, occlusion = 0;
};

FastAgreement expect_close_to_list(const TestScene& scene, const std::vector<Ray>& rays, BvhIsa isa) {
  PrimitiveList list;
  list.build(scene.primitives);
  BvhSettings settings = with_isa(isa);
  settings.exact = false;
  Bvh fast(settings);
  fast.build(scene.primitives);
  EXPECT_EQ(fast.name(), "bvh-fast");
  const double extent = length(scene.bounds().diagonal());
  FastAgreement agreement;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const Ray& ray = rays[i];
    ++agreement.rays;
    Intersection expected, actual;
    const bool expected_hit = list.intersect(ray, expected), actual_hit = fast.intersect(ray, actual);
    if (expected_hit != actual_hit) {
      ++agreement.hit_or_miss;
    } else if (expected_hit) {
      ++agreement.hits;
      // Float's error in t: about 2^-23 of the scene's extent and of the distance.
      const double tolerance = 1e-5 * (extent + expected.surface.t);
      EXPECT_NEAR(actual.surface.t, expected.surface.t, tolerance) << "ray " << i;
      EXPECT_GT(actual.surface.t, ray.t_min) << "ray " << i;
      EXPECT_LT(actual.surface.t, ray.t_max) << "ray " << i;
      if (actual.primitive != expected.primitive) {
        ++agreement.other_primitive;
      } else {
        EXPECT_LT(length(actual.surface.position - expected.surface.position), tolerance) << "ray " << i;
        EXPECT_GT(dot(actual.surface.geometric_normal, expected.surface.geometric_normal), 0.999999)
            << "ray " << i;
      }
    }
    if (fast.occluded(ray) != list.occluded(ray)) ++agreement.occlusion;
  }
  const int bound = 1 + agreement.rays / 200;  // 0.5 %
  EXPECT_LE(agreement.hit_or_miss, bound);
  EXPECT_LE(agreement.other_primitive, bound);
  EXPECT_LE(agreement.occlusion, bound);
  return agreement;
}

TEST(Bvh, FastVariantStaysCloseToTheList) {
  Pcg32 rng(53, 14);
  TestScene soup;
  soup.add_mesh(random_triangles(rng, 3000, 10, 1.0));
  TestScene sphere;  // a closed mesh: every ray from inside meets an edge's neighbourhood
  sphere.add_mesh(tessellated_sphere(40, 80, 3.0));
  TestScene mixed;  // shapes through their own tests, planes outside the tree, double vertices
  std::shared_ptr<TriangleMesh> doubles = random_triangles(rng, 800, 6, 1.5);
  for (Vec3& p : doubles->positions) p = p * (1 + 1e-9);
  mixed.add_mesh(doubles);
  for (int i = 0; i < 100; ++i)
    mixed.add(std::make_unique<Sphere>(random_in(rng, {{-6, -6, -6}, {6, 6, 6}}), uniform(rng, 0.1, 0.8)));
  mixed.add(std::make_unique<Plane>(Vec3{0, -7, 0}, Vec3{0, 1, 0}));
  std::vector<Ray> inside;
  for (int i = 0; i < 2000; ++i) {
    Ray ray{random_in(rng, {{-1, -1, -1}, {1, 1, 1}}), random_direction(rng)};
    if (i % 5 == 0) ray.t_max = uniform(rng, 1.5, 4.5);  // ending before or after the surface
    inside.push_back(ray);
  }
  const std::vector<Ray> soup_rays = random_rays(rng, soup.bounds(), 3000);
  const std::vector<Ray> mixed_rays = random_rays(rng, mixed.bounds(), 3000);
  for (BvhIsa isa : instruction_sets_of_this_cpu()) {
    SCOPED_TRACE(std::string(kBvhIsaNames.name(isa)));
    EXPECT_GT(expect_close_to_list(soup, soup_rays, isa).hits, 800);
    const FastAgreement closed = expect_close_to_list(sphere, inside, isa);
    EXPECT_GT(closed.hits, 1500);
    EXPECT_GT(expect_close_to_list(mixed, mixed_rays, isa).hits, 800);
  }
}

// The distance and the weights of one hit, and the ray's interval, which bvh-fast compares in
// double as the exact tests do (only the lanes' test is in float).
TEST(Bvh, FastVariantHitsTheTriangleInsideTheRaysInterval) {
  auto mesh = std::make_shared<TriangleMesh>();
  mesh->positions = {{-1, -1, 2}, {3, -1, 2}, {-1, 3, 2}};
  mesh->triangles = {{0, 1, 2}};
  TestScene scene;
  scene.add_mesh(mesh);
  for (BvhIsa isa : instruction_sets_of_this_cpu()) {
    SCOPED_TRACE(std::string(kBvhIsaNames.name(isa)));
    BvhSettings settings = with_isa(isa);
    settings.exact = false;
    Bvh fast(settings);
    fast.build(scene.primitives);
    Ray ray{{0.25, 0.5, 0}, {0, 0, 1}};
    Intersection hit;
    ASSERT_TRUE(fast.intersect(ray, hit));
    EXPECT_EQ(hit.surface.t, 2.0);  // exact in float as in double
    EXPECT_EQ(hit.primitive, 0u);
    EXPECT_NEAR(hit.surface.position.x, 0.25, 1e-6);
    EXPECT_NEAR(hit.surface.position.y, 0.5, 1e-6);
    EXPECT_EQ(hit.surface.position.z, 2.0);
    EXPECT_NEAR(std::fabs(hit.surface.geometric_normal.z), 1.0, 1e-12);
    EXPECT_TRUE(fast.occluded(ray));
    for (const auto& [t_min, t_max, expected] : {std::tuple{0.0, 2.0, false},
                                                 {0.0, std::nextafter(2.0, 3.0), true},
                                                 {2.0, 3.0, false},
                                                 {std::nextafter(2.0, 1.0), 3.0, true},
                                                 {1.0, 1.5, false}}) {
      ray.t_min = t_min;
      ray.t_max = t_max;
      EXPECT_EQ(fast.intersect(ray, hit), expected) << t_min << " " << t_max;
      EXPECT_EQ(fast.occluded(ray), expected) << t_min << " " << t_max;
    }
    ray = Ray{{3.5, 3.5, 0}, {0, 0, 1}};  // beside the hypotenuse
    EXPECT_FALSE(fast.intersect(ray, hit));
    EXPECT_FALSE(fast.occluded(ray));
    ray = Ray{{0.25, 0.5, 4}, {0, 0, -1}};  // the back side: two-sided, as the exact test
    ASSERT_TRUE(fast.intersect(ray, hit));
    EXPECT_EQ(hit.surface.t, 2.0);
  }
}

// Rays from beyond 1e18 of the origin test every primitive through its own exact test
// (FastSlabs' o / d would leave float's range there): the list's hit to the last bit.
TEST(Bvh, FastVariantLeavesFarRaysToTheExactTests) {
  auto mesh = std::make_shared<TriangleMesh>();
  mesh->positions = {{0, -1, -1}, {0, 3, -1}, {0, -1, 3}};
  mesh->triangles = {{0, 1, 2}};
  TestScene scene;
  scene.add_mesh(mesh);
  PrimitiveList list;
  list.build(scene.primitives);
  BvhSettings settings;
  settings.exact = false;
  Bvh fast(settings);
  fast.build(scene.primitives);
  const Ray ray{{3e18, 0.1, 0.3}, normalize(Vec3{-1, 1e-19, 3e-20})};
  Intersection expected, actual;
  ASSERT_TRUE(list.intersect(ray, expected));
  ASSERT_TRUE(fast.intersect(ray, actual));
  EXPECT_EQ(actual.surface.t, expected.surface.t);
  EXPECT_EQ(actual.surface.position, expected.surface.position);
  EXPECT_TRUE(fast.occluded(ray));
}

// bvh-fast's far end after a triangle's hit is one float step above its float t, which may have
// rounded below the true distance: a box that starts exactly there must still be entered. Found
// in review: with the far end at the float t itself both cases below failed on every ISA.
TEST(Bvh, FastVariantKeepsTiesAndCloserShapesAcrossLeaves) {
  // Two triangles with a corner V = (0, 0, z) on the ray, B (index 0) beyond V and A (index 1)
  // before it, in different leaves (fillers off the ray): both give the float t 1.59698451 (< z);
  // B's leaf box starts at z, one float step above. The tie goes to B, the lower index.
  const double a = 1.17143548f, b = 1.0224818f, z = 1.59698462f;
  auto tie = std::make_shared<TriangleMesh>();
  tie->positions = {{0, 0, z}, {-b, 0.5, 2 * z}, {0.5, -1, 2 * z}, {0, 0, z}, {a, -0.5, 0}, {-0.5, 1, 0}};
  tie->triangles = {{0, 1, 2}, {3, 4, 5}};
  for (int k = 0; k < 7; ++k) {
    for (int side = 0; side < 2; ++side) {
      const double x = -0.5 + 0.75 * (k % 2), y = 0.625 * (k % 4 < 2 ? 1 : -1),
                   filler_z = side == 0 ? z * (1.0625 + 0.125 * (k % 3)) : z * 0.125 * (k % 3);
      const auto base = static_cast<uint32_t>(tie->positions.size());
      tie->positions.push_back({x, y, filler_z});
      tie->positions.push_back({x + 0.25, y, filler_z});
      tie->positions.push_back({x, y, filler_z + 0.5 * z});
      tie->triangles.push_back({base, base + 1, base + 2});
    }
  }
  TestScene tie_scene;
  tie_scene.add_mesh(tie);
  // A quad (index 0, its exact test) 1.1e-7 closer than a slanted triangle's float t, its flat
  // box's float entry above that t.
  const Quad quad({-1, -1, 3.0685653686523438}, {2, 0, 0}, {0, 2, 0});
  auto slanted = std::make_shared<TriangleMesh>();
  slanted->positions = {{0.028137108716781656, 0.17699888865678329, 2.5789974310601247},
                        {-0.54140230204384454, -0.15704674455122333, 2.7232991530725852},
                        {0.13774062081765703, 0.14943138375161905, 3.9034005514511958}};
  slanted->triangles = {{0, 1, 2}};
  const auto slanted_triangles = make_triangles(slanted);
  const std::vector<Primitive> quad_scene = {{&quad, 0, 0}, {slanted_triangles[0].get(), 0, 1}};
  const Ray slanted_ray{{-0.27085186340846118, 0.01074239853769543, -2.0929245420265943},
                        {0.028211486167929387, 0.0088537971290239756, 0.99956276557532642}};
  SurfaceHit quad_hit;
  ASSERT_TRUE(quad.intersect(slanted_ray, quad_hit));
  for (BvhIsa isa : instruction_sets_of_this_cpu()) {
    SCOPED_TRACE(std::string(kBvhIsaNames.name(isa)));
    BvhSettings settings;
    settings.exact = false;
    settings.isa = isa;
    Bvh fast(settings);
    fast.build(tie_scene.primitives);
    Intersection hit;
    ASSERT_TRUE(fast.intersect(Ray{{0, 0, 0}, {0, 0, 1}}, hit));
    EXPECT_EQ(hit.primitive, 0u) << "t " << hit.surface.t;
    settings.max_leaf_primitives = 1;
    Bvh one_per_leaf(settings);
    one_per_leaf.build(quad_scene);
    ASSERT_TRUE(one_per_leaf.intersect(slanted_ray, hit));
    EXPECT_EQ(hit.primitive, 0u) << "the quad at " << quad_hit.t << ", the hit at " << hit.surface.t;
  }
}

}  // namespace
}  // namespace candela
