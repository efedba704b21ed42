// The Embree adapter: exact mode is the brute-force list hit for hit (ties included); native
// mode agrees with it up to rays grazing an edge (BENCH-RAYS.md).
#include "accel/embree_accelerator.h"

#include <gtest/gtest.h>

#include <limits>
#include <memory>
#include <random>

#include "accel/primitive_list.h"
#include "bench/bench_mesh.h"
#include "bench/bench_runner.h"
#include "bench/ray_sets.h"
#include "geometry/plane.h"
#include "geometry/sphere.h"
#include "geometry/triangle_mesh.h"

namespace candela {
namespace {

Vec3 random_direction(std::mt19937_64& random) {
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  const double z = 1 - 2 * uniform(random), phi = 2 * kPi * uniform(random);
  const double r = std::sqrt(std::max(0.0, 1 - z * z));
  return {r * std::cos(phi), r * std::sin(phi), z};
}

// Spheres, a triangle mesh, exact duplicates (the same shape twice and an equal copy, so ties
// at equal t must go to the lower index) and an unbounded plane.
struct MixedScene {
  std::vector<std::unique_ptr<Shape>> shapes;
  std::vector<Primitive> primitives;
  MixedScene() {
    std::mt19937_64 random(42);
    std::uniform_real_distribution<double> coordinate(-4.0, 4.0), radius(0.05, 0.8);
    for (int i = 0; i < 60; ++i) {
      const Vec3 centre{coordinate(random), coordinate(random), coordinate(random)};
      const double r = radius(random);
      shapes.push_back(std::make_unique<Sphere>(centre, r));
      if (i % 7 == 0) shapes.push_back(std::make_unique<Sphere>(centre, r));  // an equal copy
    }
    auto mesh = std::make_shared<TriangleMesh>();
    for (int i = 0; i < 150; ++i) {
      const Vec3 a{coordinate(random), coordinate(random), coordinate(random)};
      const auto base = static_cast<uint32_t>(mesh->positions.size());
      mesh->positions.push_back(a);
      mesh->positions.push_back(a + Vec3{coordinate(random), coordinate(random), coordinate(random)} * 0.3);
      mesh->positions.push_back(a + Vec3{coordinate(random), coordinate(random), coordinate(random)} * 0.3);
      mesh->triangles.push_back({base, base + 1, base + 2});
      if (i % 10 == 0) mesh->triangles.push_back({base, base + 1, base + 2});  // a duplicate triangle
    }
    for (auto& triangle : make_triangles(mesh)) shapes.push_back(std::move(triangle));
    shapes.push_back(std::make_unique<Plane>(Vec3{0, -5, 0}, Vec3{0, 1, 0}));
    for (const auto& shape : shapes) primitives.push_back({shape.get(), 0, 0});
    // The same shape at two indices.
    for (int i = 0; i < 20; i += 3) primitives.push_back(primitives[static_cast<std::size_t>(i * 5)]);
    std::shuffle(primitives.begin(), primitives.end(), random);
  }
};

TEST(EmbreeAccelerator, ExactModeEqualsTheListHitForHit) {
  const MixedScene scene;
  PrimitiveList list;
  list.build(scene.primitives);
  EmbreeAccelerator embree;
  EXPECT_EQ(embree.mode(), EmbreeAccelerator::Mode::exact);
  embree.build(scene.primitives);
  EXPECT_EQ(embree.name(), "embree");

  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> coordinate(-6.0, 6.0), uniform(0.0, 1.0);
  int hits = 0;
  for (int i = 0; i < 20000; ++i) {
    Ray ray{{coordinate(random), coordinate(random), coordinate(random)}, random_direction(random)};
    if (i % 3 == 0) ray.t_max = 8 * uniform(random);
    if (i % 5 == 0) ray.t_min = uniform(random);
    if (i % 11 == 0) ray.origin = ray.origin * 1000.0;  // far away: the float ray must still find the same
    Intersection a, b;
    const bool found_a = list.intersect(ray, a);
    const bool found_b = embree.intersect(ray, b);
    ASSERT_EQ(found_a, found_b) << "ray " << i;
    EXPECT_EQ(list.occluded(ray), embree.occluded(ray)) << "ray " << i;
    if (!found_a) continue;
    ++hits;
    ASSERT_EQ(a.primitive, b.primitive) << "ray " << i;
    ASSERT_EQ(a.surface.t, b.surface.t) << "ray " << i;
    EXPECT_EQ(a.surface.geometric_normal, b.surface.geometric_normal);
  }
  EXPECT_GT(hits, 5000);
}

TEST(EmbreeAccelerator, ExactModeBreaksTiesByLowestIndex) {
  const Sphere sphere({0, 0, 0}, 1);
  const std::vector<Primitive> primitives = {{&sphere, 0, 0}, {&sphere, 1, 0}, {&sphere, 2, 0}};
  EmbreeAccelerator embree;
  embree.build(primitives);
  Intersection hit;
  ASSERT_TRUE(embree.intersect(Ray{{0, 0, -5}, {0, 0, 1}}, hit));
  EXPECT_EQ(hit.primitive, 0u);
  EXPECT_EQ(hit.surface.t, 4.0);
}

TEST(EmbreeAccelerator, EmptySceneAndRebuild) {
  EmbreeAccelerator embree;
  embree.build({});
  Intersection hit;
  EXPECT_FALSE(embree.intersect(Ray{{0, 0, -5}, {0, 0, 1}}, hit));
  EXPECT_FALSE(embree.occluded(Ray{{0, 0, -5}, {0, 0, 1}}));
  const Sphere sphere({0, 0, 0}, 1);
  const std::vector<Primitive> primitives = {{&sphere, 0, 0}};
  embree.build(primitives);
  EXPECT_TRUE(embree.occluded(Ray{{0, 0, -5}, {0, 0, 1}}));
  EXPECT_GT(embree.report().bytes, 0u);
}

TEST(EmbreeAccelerator, NativeModeAgreesWithTheList) {
  const BenchMesh mesh = bench_sphere(4'000);
  const BenchScene scene(mesh.mesh);
  PrimitiveList list;
  list.build(scene.primitives());
  EmbreeAccelerator embree(EmbreeAccelerator::Mode::native_triangles);
  embree.build(scene.primitives());
  EXPECT_GT(embree.report().bytes, 0u);

  RaySetOptions options;
  options.width = 64;
  options.height = 64;
  std::vector<BenchRay> rays = primary_rays(mesh.bounds, options);
  const std::vector<BenchRay> incoherent = incoherent_rays(mesh.bounds, 4000, 5);
  rays.insert(rays.end(), incoherent.begin(), incoherent.end());
  int same = 0, hits = 0;
  for (const BenchRay& bench_ray : rays) {
    const Ray ray = to_ray(bench_ray);
    Intersection a, b;
    const bool found_a = list.intersect(ray, a);
    const bool found_b = embree.intersect(ray, b);
    if (found_a != found_b || (found_a && a.primitive != b.primitive)) continue;
    ++same;
    if (!found_a) continue;
    ++hits;
    // Relative to t, except for hits right next to the origin, where Embree's float t has an
    // absolute error of a few ulps of the coordinates (the sphere has radius 1).
    EXPECT_NEAR(b.surface.t, a.surface.t, 1e-5 * std::max(a.surface.t, 0.01));
    EXPECT_NEAR(dot(a.surface.geometric_normal, b.surface.geometric_normal), 1.0, 1e-5);
  }
  EXPECT_GE(same, static_cast<int>(0.999 * static_cast<double>(rays.size())));
  EXPECT_GT(hits, 2000);
  int same_occlusion = 0;
  for (const BenchRay& bench_ray : rays)
    same_occlusion += list.occluded(to_ray(bench_ray)) == embree.occluded(to_ray(bench_ray));
  EXPECT_GE(same_occlusion, static_cast<int>(0.999 * static_cast<double>(rays.size())));
}

TEST(EmbreeAccelerator, NativeModeReportsPrimitiveIndicesNotTriangleIds) {
  // The first triangle is degenerate, so make_triangles leaves it out: primitive 0 is triangle 1.
  const BenchMesh mesh = parse_bench_obj("v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 4\n", "two.obj");
  const BenchScene scene(mesh.mesh);
  EmbreeAccelerator embree(EmbreeAccelerator::Mode::native_triangles);
  embree.build(scene.primitives());
  Intersection hit;
  ASSERT_TRUE(embree.intersect(Ray{{0.25, 0.25, 1}, {0, 0, -1}}, hit));
  EXPECT_EQ(hit.primitive, 0u);
  EXPECT_EQ(scene.triangle_id(hit.primitive), 1u);
  // Native mode's t is Embree's float, computed by whichever kernel the CPU selects (on this AMD EPYC
  // with AVX2 it is 1 - 2^-24, not 1): a float's rounding, not an exact 1.
  EXPECT_NEAR(hit.surface.t, 1.0, 4 * std::numeric_limits<float>::epsilon());
}

TEST(EmbreeAccelerator, NativeModeNeedsOneMesh) {
  const Sphere sphere({0, 0, 0}, 1);
  const std::vector<Primitive> primitives = {{&sphere, 0, 0}};
  EmbreeAccelerator embree(EmbreeAccelerator::Mode::native_triangles);
  EXPECT_THROW(embree.build(primitives), std::invalid_argument);
}

}  // namespace
}  // namespace candela
