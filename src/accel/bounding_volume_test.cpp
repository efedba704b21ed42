#include "accel/bounding_volume.h"

#include <gtest/gtest.h>

#include <cmath>

#include "geometry/sphere.h"
#include "geometry/triangle_mesh.h"

namespace candela {
namespace {

TEST(BoundingVolume, SphereIsCentroidAndFarthestPoint) {
  // 000 §5.7.1: centre = centroid of the points, radius = distance to the farthest.
  const std::vector<Vec3> points = {{0, 0, 0}, {4, 0, 0}, {0, 2, 0}, {0, 0, 6}};
  const BoundingSphere sphere = BoundingSphere::around(points);
  EXPECT_NEAR(sphere.center.x, 1, 1e-15);
  EXPECT_NEAR(sphere.center.y, 0.5, 1e-15);
  EXPECT_NEAR(sphere.center.z, 1.5, 1e-15);
  EXPECT_NEAR(sphere.radius, std::sqrt(1 + 0.25 + 4.5 * 4.5), 1e-9);
}

TEST(BoundingVolume, SphereTestRespectsTheRayInterval) {
  const BoundingSphere sphere{{0, 0, -10}, 1};
  Ray ray{{0, 0, 0}, {0, 0, -1}};
  EXPECT_TRUE(sphere.hit_by(ray));
  ray.t_max = 8.9;  // ends before the sphere
  EXPECT_FALSE(sphere.hit_by(ray));
  EXPECT_FALSE(sphere.hit_by(Ray{{0, 1.01, 0}, {0, 0, -1}}));
  EXPECT_FALSE(sphere.hit_by(Ray{{0, 0, 0}, {0, 0, 1}}));   // behind
  EXPECT_TRUE(sphere.hit_by(Ray{{0, 0, -10}, {1, 0, 0}}));  // from inside
}

TEST(BoundingVolume, SlabsAreExactForASphere) {
  // Along each of the 7 normals a sphere of radius r about c spans n·c ± r.
  std::vector<Vec3> points;
  bounding_points(Sphere({1, 2, 3}, 2), points);
  const KayKajiyaSlabs slabs = KayKajiyaSlabs::around(points);
  for (int i = 0; i < 7; ++i) {
    const double centre = dot(KayKajiyaSlabs::kNormals[i], Vec3{1, 2, 3});
    EXPECT_NEAR(slabs.lower[i], centre - 2, 1e-9);
    EXPECT_NEAR(slabs.upper[i], centre + 2, 1e-9);
  }
  // The diagonal slabs cut the corners a box would keep: a ray through the box corner region
  // (inside the box, outside the sphere's diagonal slab) is rejected.
  const Vec3 corner_region = Vec3{1, 2, 3} + Vec3{1.9, 1.9, 1.9};
  EXPECT_FALSE(slabs.hit_by(Ray{corner_region + Vec3{0, 0, 10}, {0, 0, -1}, 0, 10.05}));
  EXPECT_TRUE(slabs.hit_by(Ray{{1, 2, 20}, {0, 0, -1}}));
}

TEST(BoundingVolume, SlabsOfATriangleUseItsVertices) {
  auto mesh = std::make_shared<TriangleMesh>();
  mesh->positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  mesh->triangles = {{0, 1, 2}};
  const MeshTriangle triangle(mesh, 0);
  std::vector<Vec3> points;
  bounding_points(triangle, points);
  ASSERT_EQ(points.size(), 3u);
  const KayKajiyaSlabs slabs = KayKajiyaSlabs::around(points);
  // Along (1,1,1)/√3 the triangle spans [0, 1/√3].
  EXPECT_NEAR(slabs.lower[3], 0, 1e-9);
  EXPECT_NEAR(slabs.upper[3], 1 / std::sqrt(3.0), 1e-9);
  // A ray parallel to z through (0.8, 0.8): inside the box [0,1]², outside the triangle's
  // diagonal slab x + y <= 1 — rejected by the slabs.
  EXPECT_FALSE(slabs.hit_by(Ray{{0.8, 0.8, 5}, {0, 0, -1}}));
  EXPECT_TRUE(slabs.hit_by(Ray{{0.2, 0.2, 5}, {0, 0, -1}}));
}

TEST(BoundingVolume, NamesRoundTrip) {
  for (const char* name : {"none", "sphere", "box", "slabs"}) {
    const auto kind = kBoundingVolumeNames.value(name);
    ASSERT_TRUE(kind);
    EXPECT_EQ(kBoundingVolumeNames.name(*kind), name);
  }
  EXPECT_FALSE(kBoundingVolumeNames.value("capsule"));
}

}  // namespace
}  // namespace candela
