#include "geometry/sphere.h"

#include <gtest/gtest.h>

#include <cmath>

#include "geometry/transformed_shape.h"
#include "math/transform.h"
#include "shape_test_support.h"

namespace candela {
namespace {

using candela::testing::make_ray;

TEST(Sphere, HitFromOutsideTakesNearRoot) {
  const Sphere sphere({0, 0, -5}, 1);
  SurfaceHit hit;
  ASSERT_TRUE(sphere.intersect(make_ray({0, 0, 0}, {0, 0, -1}), hit));
  EXPECT_DOUBLE_EQ(hit.t, 4.0);
  EXPECT_NEAR(hit.position.z, -4.0, 1e-12);
  EXPECT_NEAR(hit.geometric_normal.z, 1.0, 1e-12);
}

TEST(Sphere, MissWhenClosestApproachIsOutside) {
  const Sphere sphere({0, 0, -5}, 1);
  SurfaceHit hit;
  EXPECT_FALSE(sphere.intersect(make_ray({0, 1.0001, 0}, {0, 0, -1}), hit));
}

TEST(Sphere, GrazingRayDoesNotCount) {
  // 000 §5.6.1: gamma = 0 (tangent) is grouped with the miss case.
  const Sphere sphere({0, 0, -5}, 1);
  SurfaceHit hit;
  EXPECT_FALSE(sphere.intersect(make_ray({0, 1, 0}, {0, 0, -1}), hit));
}

TEST(Sphere, OriginInsideTakesFarRoot) {
  const Sphere sphere({1, 2, 3}, 2);
  SurfaceHit hit;
  ASSERT_TRUE(sphere.intersect(make_ray({1, 2, 3}, {1, 0, 0}), hit));
  EXPECT_DOUBLE_EQ(hit.t, 2.0);
  EXPECT_NEAR(hit.geometric_normal.x, 1.0, 1e-12);  // outward, the caller flips as needed
}

TEST(Sphere, SphereBehindOriginIsMissed) {
  const Sphere sphere({0, 0, 5}, 1);
  SurfaceHit hit;
  EXPECT_FALSE(sphere.intersect(make_ray({0, 0, 0}, {0, 0, -1}), hit));
  EXPECT_FALSE(sphere.occluded(make_ray({0, 0, 0}, {0, 0, -1})));
}

TEST(Sphere, OriginOnSurfaceDoesNotHitItself) {
  // 000 §5.6.1: a ray starting exactly on the sphere does not intersect it at its origin.
  const Sphere sphere({0, 0, 0}, 1);
  SurfaceHit hit;
  Ray outward = make_ray({0, 0, 1}, {0, 0, 1});
  outward.t_min = 1e-9;
  EXPECT_FALSE(sphere.intersect(outward, hit));
  Ray inward = make_ray({0, 0, 1}, {0, 0, -1});
  inward.t_min = 1e-9;
  ASSERT_TRUE(sphere.intersect(inward, hit));
  EXPECT_NEAR(hit.t, 2.0, 1e-12);
}

TEST(Sphere, RespectsTMax) {
  const Sphere sphere({0, 0, -5}, 1);
  Ray ray = make_ray({0, 0, 0}, {0, 0, -1});
  ray.t_max = 3.9;
  EXPECT_FALSE(sphere.occluded(ray));
  ray.t_max = 4.1;
  EXPECT_TRUE(sphere.occluded(ray));
}

TEST(Sphere, UvAndDerivativesAreConsistent) {
  const Sphere sphere({0, 0, 0}, 2);
  SurfaceHit hit;
  ASSERT_TRUE(sphere.intersect(make_ray({5, 0, 0}, {-1, 0, 0}), hit));
  EXPECT_NEAR(hit.uv.x, 0.0, 1e-12);
  EXPECT_NEAR(hit.uv.y, 0.5, 1e-12);
  // dpdu x dpdv points outward.
  EXPECT_GT(dot(cross(hit.dpdu, hit.dpdv), hit.geometric_normal), 0);
}

TEST(Sphere, RejectsNonPositiveRadius) {
  EXPECT_THROW(Sphere({0, 0, 0}, 0), std::invalid_argument);
  EXPECT_THROW(Sphere({0, 0, 0}, -1), std::invalid_argument);
  EXPECT_THROW(Sphere({0, 0, 0}, std::nan("")), std::invalid_argument);
}

TEST(Sphere, TransformedScaledSphereIsAnEllipsoid) {
  // Unit sphere scaled by (2, 1, 1), moved to x = 10: a ray along -x from x = 20 hits x = 12.
  const TransformedShape ellipsoid(std::make_unique<Sphere>(Vec3{0, 0, 0}, 1.0),
                                   Transform::translate({10, 0, 0}) * Transform::scale({2, 1, 1}));
  SurfaceHit hit;
  ASSERT_TRUE(ellipsoid.intersect(make_ray({20, 0, 0}, {-1, 0, 0}), hit));
  EXPECT_NEAR(hit.t, 8.0, 1e-12);
  EXPECT_NEAR(hit.position.x, 12.0, 1e-12);
  EXPECT_NEAR(hit.geometric_normal.x, 1.0, 1e-12);
  // Off-axis: the normal of the ellipsoid x²/4 + y² = 1 at (10+√2, √0.5) is ∝ (x/4, y).
  ASSERT_TRUE(ellipsoid.intersect(make_ray({10 + std::sqrt(2.0), 5, 0}, {0, -1, 0}), hit));
  EXPECT_NEAR(hit.position.y, std::sqrt(0.5), 1e-12);
  const Vec3 expected = normalize(Vec3{std::sqrt(2.0) / 4, std::sqrt(0.5), 0});
  EXPECT_NEAR(dot(hit.geometric_normal, expected), 1.0, 1e-12);
  const Bounds3 bounds = ellipsoid.bounds();
  EXPECT_NEAR(bounds.lower.x, 8.0, 1e-12);
  EXPECT_NEAR(bounds.upper.x, 12.0, 1e-12);
}

}  // namespace
}  // namespace candela
