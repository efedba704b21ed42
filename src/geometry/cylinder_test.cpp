#include "geometry/cylinder.h"

#include <gtest/gtest.h>

#include <cmath>

#include "geometry/transformed_shape.h"
#include "math/constants.h"
#include "math/transform.h"
#include "shape_test_support.h"

namespace candela {
namespace {

using candela::testing::expect_vec_near;
using candela::testing::make_ray;

// Axis +z from z = 0 to z = 2, radius 1; orthonormal_basis((0, 0, 1)) = (1, 0, 0), (0, 1, 0),
// so u is the angle from +x about +z.
const Cylinder kCapped({0, 0, 0}, {0, 0, 2}, 1);
const Cylinder kOpen({0, 0, 0}, {0, 0, 2}, 1, false);

TEST(Cylinder, SideHit) {
  SurfaceHit hit;
  ASSERT_TRUE(kCapped.intersect(make_ray({5, 0, 1}, {-1, 0, 0}), hit));
  EXPECT_DOUBLE_EQ(hit.t, 4.0);
  expect_vec_near(hit.position, {1, 0, 1}, 1e-12);
  expect_vec_near(hit.geometric_normal, {1, 0, 0}, 1e-12);
  EXPECT_NEAR(hit.uv.x, 0.0, 1e-12);
  EXPECT_NEAR(hit.uv.y, 0.5, 1e-12);
  ASSERT_TRUE(kCapped.intersect(make_ray({0, 5, 0.5}, {0, -1, 0}), hit));
  EXPECT_DOUBLE_EQ(hit.t, 4.0);
  expect_vec_near(hit.geometric_normal, {0, 1, 0}, 1e-12);
  EXPECT_NEAR(hit.uv.x, 0.25, 1e-12);
  EXPECT_NEAR(hit.uv.y, 0.25, 1e-12);
  expect_vec_near(hit.dpdu, {-2 * kPi, 0, 0}, 1e-12);
  expect_vec_near(hit.dpdv, {0, 0, 2}, 1e-12);
  // Off the axis: x = 0.6 meets the side at y = ±0.8.
  ASSERT_TRUE(kCapped.intersect(make_ray({0.6, -5, 1}, {0, 1, 0}), hit));
  EXPECT_NEAR(hit.t, 4.2, 1e-12);
  expect_vec_near(hit.geometric_normal, {0.6, -0.8, 0}, 1e-12);
}

TEST(Cylinder, CapHits) {
  SurfaceHit hit;
  ASSERT_TRUE(kCapped.intersect(make_ray({0.5, 0, 5}, {0, 0, -1}), hit));
  EXPECT_DOUBLE_EQ(hit.t, 3.0);
  expect_vec_near(hit.position, {0.5, 0, 2}, 1e-12);
  expect_vec_near(hit.geometric_normal, {0, 0, 1}, 1e-15);
  EXPECT_NEAR(hit.uv.y, 0.5, 1e-12);  // 1 - r / radius
  EXPECT_GT(dot(cross(hit.dpdu, hit.dpdv), hit.geometric_normal), 0);
  ASSERT_TRUE(kCapped.intersect(make_ray({0, 0.5, -5}, {0, 0, 1}), hit));
  EXPECT_DOUBLE_EQ(hit.t, 5.0);
  expect_vec_near(hit.geometric_normal, {0, 0, -1}, 1e-15);
  EXPECT_NEAR(hit.uv.x, 0.75, 1e-12);  // counter-clockwise seen from below
  EXPECT_GT(dot(cross(hit.dpdu, hit.dpdv), hit.geometric_normal), 0);
}

TEST(Cylinder, DerivativesPointOutwardOnTheSide) {
  SurfaceHit hit;
  ASSERT_TRUE(kCapped.intersect(make_ray({-3, -4, 1.5}, {3, 4, 0}), hit));
  EXPECT_NEAR(hit.t, 4.0, 1e-12);
  EXPECT_NEAR(dot(hit.geometric_normal, Vec3{-0.6, -0.8, 0}), 1.0, 1e-12);
  EXPECT_GT(dot(cross(hit.dpdu, hit.dpdv), hit.geometric_normal), 0);
}

TEST(Cylinder, Misses) {
  SurfaceHit hit;
  EXPECT_FALSE(kCapped.intersect(make_ray({5, 1.5, 1}, {-1, 0, 0}), hit));
  EXPECT_FALSE(kCapped.intersect(make_ray({5, 0, 2.5}, {-1, 0, 0}), hit));   // above
  EXPECT_FALSE(kCapped.intersect(make_ray({5, 0, -0.1}, {-1, 0, 0}), hit));  // below
  EXPECT_FALSE(kCapped.intersect(make_ray({5, 0, 1}, {1, 0, 0}), hit));      // behind
  EXPECT_FALSE(kCapped.occluded(make_ray({0, 0, 5}, {0, 0, 1})));
}

TEST(Cylinder, GrazingRays) {
  // A ray tangent to the side misses (as for the sphere); the caps are closed discs, so a ray
  // along the axis on the surface hits the rim of a cap (and misses an open cylinder).
  SurfaceHit hit;
  EXPECT_FALSE(kCapped.intersect(make_ray({5, 1, 1}, {-1, 0, 0}), hit));
  ASSERT_TRUE(kCapped.intersect(make_ray({1, 0, 5}, {0, 0, -1}), hit));
  EXPECT_DOUBLE_EQ(hit.t, 3.0);
  expect_vec_near(hit.geometric_normal, {0, 0, 1}, 1e-15);
  EXPECT_FALSE(kOpen.intersect(make_ray({1, 0, 5}, {0, 0, -1}), hit));
}

TEST(Cylinder, OriginInsideHitsTheFarSurface) {
  SurfaceHit hit;
  ASSERT_TRUE(kCapped.intersect(make_ray({0, 0, 1}, {1, 0, 0}), hit));
  EXPECT_DOUBLE_EQ(hit.t, 1.0);
  expect_vec_near(hit.geometric_normal, {1, 0, 0}, 1e-12);
  ASSERT_TRUE(kCapped.intersect(make_ray({0, 0, 1.5}, {0, 0, 1}), hit));
  EXPECT_DOUBLE_EQ(hit.t, 0.5);
  expect_vec_near(hit.geometric_normal, {0, 0, 1}, 1e-15);
  ASSERT_TRUE(kCapped.intersect(make_ray({0, 0, 1.5}, {0, 0, -1}), hit));
  EXPECT_DOUBLE_EQ(hit.t, 1.5);
  expect_vec_near(hit.geometric_normal, {0, 0, -1}, 1e-15);
}

TEST(Cylinder, OpenCylinderShowsItsInside) {
  SurfaceHit hit;
  // Through the open top, down to the inside of the side at (1, 0, 1); the normal stays
  // outward.
  ASSERT_TRUE(kOpen.intersect(make_ray({0, 0, 5}, {1, 0, -4}), hit));
  EXPECT_NEAR(hit.t, std::sqrt(17.0), 1e-12);
  expect_vec_near(hit.position, {1, 0, 1}, 1e-12);
  expect_vec_near(hit.geometric_normal, {1, 0, 0}, 1e-12);
  EXPECT_FALSE(kOpen.intersect(make_ray({0.5, 0, 5}, {0, 0, -1}), hit));
}

TEST(Cylinder, RespectsTMinAndTMax) {
  Ray ray = make_ray({5, 0, 1}, {-1, 0, 0});
  ray.t_max = 4.0;
  EXPECT_FALSE(kCapped.occluded(ray));
  ray.t_max = 4.01;
  EXPECT_TRUE(kCapped.occluded(ray));
  ray.t_min = 4.5;
  ray.t_max = kInfinity;
  SurfaceHit hit;
  ASSERT_TRUE(kCapped.intersect(ray, hit));
  EXPECT_DOUBLE_EQ(hit.t, 6.0);
  expect_vec_near(hit.geometric_normal, {-1, 0, 0}, 1e-12);
}

TEST(Cylinder, TiltedAxis) {
  // Axis from the origin to (3, 4, 0) (height 5), radius 1: the ray down through (1.5, 2, 5)
  // crosses the axis at right angles and meets the side at z = 1.
  const Cylinder cylinder({0, 0, 0}, {3, 4, 0}, 1);
  SurfaceHit hit;
  ASSERT_TRUE(cylinder.intersect(make_ray({1.5, 2, 5}, {0, 0, -1}), hit));
  EXPECT_NEAR(hit.t, 4.0, 1e-12);
  expect_vec_near(hit.geometric_normal, {0, 0, 1}, 1e-12);
  EXPECT_NEAR(hit.uv.y, 0.5, 1e-12);
  // Along the axis from beyond the cap: the cap disc at (3, 4, 0), normal +axis.
  ASSERT_TRUE(cylinder.intersect(make_ray({6, 8, 0}, {-3, -4, 0}), hit));
  EXPECT_NEAR(hit.t, 5.0, 1e-12);
  expect_vec_near(hit.geometric_normal, {0.6, 0.8, 0}, 1e-12);
  // Bounds: the end discs reach 1 * sqrt(1 - 0.36) = 0.8 in x, 0.6 in y, 1 in z.
  const Bounds3 bounds = cylinder.bounds();
  expect_vec_near(bounds.lower, {-0.8, -0.6, -1}, 1e-12);
  expect_vec_near(bounds.upper, {3.8, 4.6, 1}, 1e-12);
}

TEST(Cylinder, Bounds) {
  const Bounds3 bounds = kCapped.bounds();
  expect_vec_near(bounds.lower, {-1, -1, 0}, 1e-15);
  expect_vec_near(bounds.upper, {1, 1, 2}, 1e-15);
}

TEST(Cylinder, RejectsBadArguments) {
  EXPECT_THROW(Cylinder({0, 0, 0}, {0, 0, 1}, 0), std::invalid_argument);
  EXPECT_THROW(Cylinder({0, 0, 0}, {0, 0, 1}, -1), std::invalid_argument);
  EXPECT_THROW(Cylinder({0, 0, 0}, {0, 0, 1}, std::nan("")), std::invalid_argument);
  EXPECT_THROW(Cylinder({1, 2, 3}, {1, 2, 3}, 1), std::invalid_argument);
  EXPECT_THROW(Cylinder({0, 0, 0}, {0, 0, kInfinity}, 1), std::invalid_argument);
}

TEST(Cylinder, TransformedEllipticCylinder) {
  // Scaled by (2, 1, 3): an elliptic cylinder 4 wide in x, 6 high.
  const TransformedShape cylinder(std::make_unique<Cylinder>(Vec3{0, 0, 0}, Vec3{0, 0, 2}, 1.0),
                                  Transform::translate({0, 0, 1}) * Transform::scale({2, 1, 3}));
  SurfaceHit hit;
  ASSERT_TRUE(cylinder.intersect(make_ray({5, 0, 4}, {-1, 0, 0}), hit));
  EXPECT_NEAR(hit.t, 3.0, 1e-12);
  expect_vec_near(hit.geometric_normal, {1, 0, 0}, 1e-12);
  ASSERT_TRUE(cylinder.intersect(make_ray({1.5, 0, 10}, {0, 0, -1}), hit));
  EXPECT_NEAR(hit.t, 3.0, 1e-12);  // top at z = 1 + 6
  expect_vec_near(hit.geometric_normal, {0, 0, 1}, 1e-12);
  EXPECT_FALSE(cylinder.intersect(make_ray({0, 1.1, 10}, {0, 0, -1}), hit));
  EXPECT_NEAR(cylinder.bounds().upper.z, 7.0, 1e-12);
}

}  // namespace
}  // namespace candela
