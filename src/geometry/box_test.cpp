#include "geometry/box.h"

#include <gtest/gtest.h>

#include <cmath>

#include "geometry/transformed_shape.h"
#include "math/transform.h"
#include "shape_test_support.h"

namespace candela {
namespace {

using candela::testing::make_ray;

const Box kCube({-1, -1, -1}, {1, 1, 1});

TEST(Box, HitTheNearFace) {
  SurfaceHit hit;
  ASSERT_TRUE(kCube.intersect(make_ray({5, 0.5, -0.5}, {-1, 0, 0}), hit));
  EXPECT_DOUBLE_EQ(hit.t, 4.0);
  EXPECT_EQ(hit.position, (Vec3{1, 0.5, -0.5}));
  EXPECT_EQ(hit.geometric_normal, (Vec3{1, 0, 0}));
  EXPECT_EQ(hit.shading_normal, (Vec3{1, 0, 0}));
  // Upper x face: u along y, v along z.
  EXPECT_NEAR(hit.uv.x, 0.75, 1e-12);
  EXPECT_NEAR(hit.uv.y, 0.25, 1e-12);
  EXPECT_EQ(hit.dpdu, (Vec3{0, 2, 0}));
  EXPECT_EQ(hit.dpdv, (Vec3{0, 0, 2}));
}

TEST(Box, LowerFaceNormalAndUv) {
  const Box box({0, 0, 0}, {2, 4, 8});
  SurfaceHit hit;
  ASSERT_TRUE(box.intersect(make_ray({0.5, 3, -5}, {0, 0, 1}), hit));
  EXPECT_DOUBLE_EQ(hit.t, 5.0);
  EXPECT_EQ(hit.geometric_normal, (Vec3{0, 0, -1}));
  // Lower z face: u along y, v along x, so that dpdu x dpdv = -z.
  EXPECT_NEAR(hit.uv.x, 0.75, 1e-12);
  EXPECT_NEAR(hit.uv.y, 0.25, 1e-12);
  EXPECT_EQ(cross(hit.dpdu, hit.dpdv), (Vec3{0, 0, -8}));
}

TEST(Box, DerivativesPointOutwardOnEveryFace) {
  const Vec3 directions[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (const Vec3& direction : directions) {
    SurfaceHit hit;
    ASSERT_TRUE(kCube.intersect(make_ray(direction * -5 + Vec3{0.1, 0.2, 0.3}, direction), hit));
    EXPECT_EQ(hit.geometric_normal, -direction);
    EXPECT_DOUBLE_EQ(dot(cross(hit.dpdu, hit.dpdv), hit.geometric_normal), 4.0);
  }
}

TEST(Box, ObliqueHit) {
  // From (-3, -2, 0) along (1, 1, 0): x reaches -1 at t = 2√2, y reaches -1 at t = √2; the
  // entry is the later one, through the x = -1 face at (-1, 0, 0).
  SurfaceHit hit;
  ASSERT_TRUE(kCube.intersect(make_ray({-3, -2, 0}, {1, 1, 0}), hit));
  EXPECT_NEAR(hit.t, 2 * std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(hit.position.y, 0.0, 1e-12);
  EXPECT_EQ(hit.geometric_normal, (Vec3{-1, 0, 0}));
}

TEST(Box, Misses) {
  SurfaceHit hit;
  EXPECT_FALSE(kCube.intersect(make_ray({5, 1.5, 0}, {-1, 0, 0}), hit));
  EXPECT_FALSE(kCube.intersect(make_ray({-3, 0, 0}, {1, 2, 0}), hit));  // passes the corner
  EXPECT_FALSE(kCube.intersect(make_ray({5, 0, 0}, {1, 0, 0}), hit));   // behind
  EXPECT_FALSE(kCube.occluded(make_ray({5, 0, 0}, {1, 0, 0})));
}

TEST(Box, OriginInsideHitsTheFarFace) {
  SurfaceHit hit;
  ASSERT_TRUE(kCube.intersect(make_ray({0, 0, 0}, {0, 1, 0}), hit));
  EXPECT_DOUBLE_EQ(hit.t, 1.0);
  EXPECT_EQ(hit.geometric_normal, (Vec3{0, 1, 0}));
  ASSERT_TRUE(kCube.intersect(make_ray({0.5, 0, 0}, {-1, -1, 0}), hit));
  EXPECT_NEAR(hit.t, std::sqrt(2.0), 1e-12);  // y = -1 at x = -0.5
  EXPECT_EQ(hit.geometric_normal, (Vec3{0, -1, 0}));
}

TEST(Box, TMinSkipsToTheExitAndTMaxClips) {
  SurfaceHit hit;
  Ray ray = make_ray({5, 0, 0}, {-1, 0, 0});
  ray.t_min = 4.5;
  ASSERT_TRUE(kCube.intersect(ray, hit));
  EXPECT_DOUBLE_EQ(hit.t, 6.0);
  EXPECT_EQ(hit.geometric_normal, (Vec3{-1, 0, 0}));
  ray.t_min = 0;
  ray.t_max = 4.0;
  EXPECT_FALSE(kCube.occluded(ray));
  ray.t_max = 4.01;
  EXPECT_TRUE(kCube.occluded(ray));
}

TEST(Box, TouchingRaysHitTheClosedBox) {
  // Grazing convention (as Bounds3::intersect): the box is closed, so a ray running along a
  // face, or touching only an edge, hits where it first touches the box.
  SurfaceHit hit;
  ASSERT_TRUE(kCube.intersect(make_ray({-5, 0.5, 1}, {1, 0, 0}), hit));  // in the face z = 1
  EXPECT_DOUBLE_EQ(hit.t, 4.0);
  EXPECT_EQ(hit.geometric_normal, (Vec3{-1, 0, 0}));
  // Along (1, 1, 0) from (-2, 0, 0): touches only the edge x = -1, y = 1 at t = √2.
  ASSERT_TRUE(kCube.intersect(make_ray({-2, 0, 0}, {1, 1, 0}), hit));
  EXPECT_NEAR(hit.t, std::sqrt(2.0), 1e-12);
  EXPECT_EQ(hit.geometric_normal, (Vec3{-1, 0, 0}));
  EXPECT_FALSE(kCube.intersect(make_ray({-2, 1e-9, 0}, {1, 1, 0}), hit));
  EXPECT_FALSE(kCube.intersect(make_ray({-5, 0.5, 1 + 1e-12}, {1, 0, 0}), hit));
}

TEST(Box, RejectsBadArguments) {
  EXPECT_THROW(Box({0, 0, 0}, {1, 0, 1}), std::invalid_argument);  // flat
  EXPECT_THROW(Box({0, 0, 0}, {1, -1, 1}), std::invalid_argument);
  EXPECT_THROW(Box({0, 0, std::nan("")}, {1, 1, 1}), std::invalid_argument);
  EXPECT_THROW(Box({0, 0, 0}, {1, 1, kInfinity}), std::invalid_argument);
}

TEST(Box, TransformedRotatedBox) {
  // The cube turned 45° about +z and moved to (10, 0, 0): the face that was +x now faces
  // (1, 1, 0)/√2, at distance 1 from the centre.
  const TransformedShape box(std::make_unique<Box>(Vec3{-1, -1, -1}, Vec3{1, 1, 1}),
                             Transform::translate({10, 0, 0}) * Transform::rotate(45, {0, 0, 1}));
  SurfaceHit hit;
  ASSERT_TRUE(box.intersect(make_ray({15, 5, 0}, {-1, -1, 0}), hit));
  EXPECT_NEAR(hit.t, 5 * std::sqrt(2.0) - 1, 1e-12);
  EXPECT_NEAR(dot(hit.geometric_normal, normalize(Vec3{1, 1, 0})), 1.0, 1e-12);
  // Along -x the ray meets the vertical edge at x = 10 + √2.
  ASSERT_TRUE(box.intersect(make_ray({20, 0, 0.5}, {-1, 0, 0}), hit));
  EXPECT_NEAR(hit.t, 10 - std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(box.bounds().upper.x, 10 + std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(box.bounds().upper.y, std::sqrt(2.0), 1e-12);
}

}  // namespace
}  // namespace candela
