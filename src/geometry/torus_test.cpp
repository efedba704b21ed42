#include "geometry/torus.h"

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

// R = 3, r = 1 about +z; orthonormal_basis((0, 0, 1)) = (1, 0, 0), (0, 1, 0).
const Torus kRing({0, 0, 0}, {0, 0, 1}, 3, 1);

TEST(Torus, EquatorialRayMeetsAllFourRoots) {
  // Along +x from x = -10 through the centre: x = -4, -2, 2, 4, i.e. t = 6, 8, 12, 14, with
  // outward normals -x, +x (towards the hole), -x, +x. t_min steps past each in turn.
  const double expected_t[4] = {6, 8, 12, 14};
  const double expected_nx[4] = {-1, 1, -1, 1};
  Ray ray = make_ray({-10, 0, 0}, {1, 0, 0});
  for (int i = 0; i < 4; ++i) {
    SurfaceHit hit;
    ASSERT_TRUE(kRing.intersect(ray, hit)) << i;
    EXPECT_NEAR(hit.t, expected_t[i], 1e-12) << i;
    expect_vec_near(hit.position, {expected_t[i] - 10, 0, 0}, 1e-12);
    expect_vec_near(hit.geometric_normal, {expected_nx[i], 0, 0}, 1e-12);
    ray.t_min = expected_t[i] + 0.5;
  }
  SurfaceHit hit;
  EXPECT_FALSE(kRing.intersect(ray, hit));
}

TEST(Torus, RayAlongTheAxisPassesThroughTheHole) {
  SurfaceHit hit;
  EXPECT_FALSE(kRing.intersect(make_ray({0, 0, 10}, {0, 0, -1}), hit));
  EXPECT_FALSE(kRing.occluded(make_ray({0, 0, -10}, {0, 0, 1})));
  // Parallel to the axis through the ring at radius 3.5: hits the top of the tube at height
  // sqrt(1 - 0.25).
  ASSERT_TRUE(kRing.intersect(make_ray({3.5, 0, 10}, {0, 0, -1}), hit));
  EXPECT_NEAR(hit.t, 10 - std::sqrt(0.75), 1e-12);
  expect_vec_near(hit.geometric_normal, {0.5, 0, std::sqrt(0.75)}, 1e-12);
}

TEST(Torus, UvAndDerivatives) {
  SurfaceHit hit;
  ASSERT_TRUE(kRing.intersect(make_ray({3, 0, 10}, {0, 0, -1}), hit));  // top of the tube
  EXPECT_NEAR(hit.t, 9.0, 1e-12);
  expect_vec_near(hit.geometric_normal, {0, 0, 1}, 1e-12);
  EXPECT_NEAR(hit.uv.x, 0.0, 1e-12);
  EXPECT_NEAR(hit.uv.y, 0.25, 1e-12);
  ASSERT_TRUE(kRing.intersect(make_ray({0, 10, 0}, {0, -1, 0}), hit));  // outer equator
  EXPECT_NEAR(hit.t, 6.0, 1e-12);
  expect_vec_near(hit.geometric_normal, {0, 1, 0}, 1e-12);
  EXPECT_NEAR(hit.uv.x, 0.25, 1e-12);
  EXPECT_NEAR(hit.uv.y, 0.0, 1e-12);
  // dp/du = 2π (R + r) (-1, 0, 0) there; dp/dv = 2π r (0, 0, 1).
  expect_vec_near(hit.dpdu, {-8 * kPi, 0, 0}, 1e-12);
  expect_vec_near(hit.dpdv, {0, 0, 2 * kPi}, 1e-12);
  // Aimed at (3.2, 1.1, 0), inside the tube.
  ASSERT_TRUE(kRing.intersect(make_ray({0, 0, 5}, {3.2, 1.1, -5}), hit));
  EXPECT_GT(dot(cross(hit.dpdu, hit.dpdv), hit.geometric_normal), 0);
}

TEST(Torus, OriginInsideTheTube) {
  SurfaceHit hit;
  ASSERT_TRUE(kRing.intersect(make_ray({3, 0, 0}, {0, 0, 1}), hit));
  EXPECT_NEAR(hit.t, 1.0, 1e-12);
  expect_vec_near(hit.geometric_normal, {0, 0, 1}, 1e-12);
  ASSERT_TRUE(kRing.intersect(make_ray({3, 0, 0}, {-1, 0, 0}), hit));
  EXPECT_NEAR(hit.t, 1.0, 1e-12);
  expect_vec_near(hit.geometric_normal, {-1, 0, 0}, 1e-12);  // outward, towards the hole
  ASSERT_TRUE(kRing.intersect(make_ray({0, 3, 0.5}, {0, 1, 0}), hit));
  EXPECT_NEAR(hit.t, std::sqrt(0.75), 1e-12);
}

TEST(Torus, BehindAndTMax) {
  SurfaceHit hit;
  EXPECT_FALSE(kRing.intersect(make_ray({10, 0, 0}, {1, 0, 0}), hit));
  Ray ray = make_ray({-10, 0, 0}, {1, 0, 0});
  ray.t_max = 6.0;
  EXPECT_FALSE(kRing.occluded(ray));
  ray.t_max = 6.01;
  EXPECT_TRUE(kRing.occluded(ray));
  ray.t_max = 3.0;  // ends before the bounding sphere
  EXPECT_FALSE(kRing.occluded(ray));
}

TEST(Torus, NearlyTangentRays) {
  // Grazing: an exactly tangent ray (a double root) may go either way; just below the top of
  // the tube (z = 1 - 1e-6) the ray hits at x = -(3 + sqrt(1 - z^2)), just above it misses.
  const double z = 1 - 1e-6;
  SurfaceHit hit;
  ASSERT_TRUE(kRing.intersect(make_ray({-10, 0, z}, {1, 0, 0}), hit));
  EXPECT_NEAR(hit.t, 7 - std::sqrt(1 - z * z), 1e-9);
  EXPECT_FALSE(kRing.intersect(make_ray({-10, 0, 1 + 1e-6}, {1, 0, 0}), hit));
  // Parallel to the axis just outside / inside the inner equator (rho = 2).
  ASSERT_TRUE(kRing.intersect(make_ray({2 + 1e-6, 0, 10}, {0, 0, -1}), hit));
  EXPECT_NEAR(hit.t, 10 - std::sqrt(1 - (1 - 1e-6) * (1 - 1e-6)), 1e-9);
  EXPECT_FALSE(kRing.intersect(make_ray({2 - 1e-6, 0, 10}, {0, 0, -1}), hit));
}

TEST(Torus, FarAwayRaysStayAccurate) {
  // 1e4 units away the raw quartic would have coefficients of 1e16; moving the origin to the
  // bounding sphere first keeps the roots accurate.
  SurfaceHit hit;
  ASSERT_TRUE(kRing.intersect(make_ray({1e4, 0, 0}, {-1, 0, 0}), hit));
  EXPECT_NEAR(hit.t, 1e4 - 4, 1e-9);
  // Off centre in the equatorial plane: the annulus 2 <= rho <= 4 is met at x = √15.
  ASSERT_TRUE(kRing.intersect(make_ray({1e4, 1, 0}, {-1, 0, 0}), hit));
  EXPECT_NEAR(hit.t, 1e4 - std::sqrt(15.0), 1e-9);
  expect_vec_near(hit.geometric_normal, Vec3{std::sqrt(15.0), 1, 0} / 4, 1e-9);
  // Down the outward normal at tube angle 45°, longitude 30°, from 1e4 (and 1e6) away.
  const double phi = kPi / 6, theta = kPi / 4;
  const Vec3 normal{std::cos(theta) * std::cos(phi), std::cos(theta) * std::sin(phi), std::sin(theta)};
  const Vec3 point = Vec3{3 * std::cos(phi), 3 * std::sin(phi), 0} + normal;
  for (const double distance : {1e4, 1e6}) {
    ASSERT_TRUE(kRing.intersect(Ray{point + normal * distance, -normal}, hit)) << distance;
    EXPECT_NEAR(hit.t, distance, 1e-13 * distance) << distance;
    expect_vec_near(hit.position, point, 1e-13 * distance);
    EXPECT_NEAR(dot(hit.geometric_normal, normal), 1.0, 1e-12) << distance;
    EXPECT_NEAR(hit.uv.x, 1.0 / 12, 1e-9);
    EXPECT_NEAR(hit.uv.y, 1.0 / 8, 1e-9);
  }
}

TEST(Torus, AxisArgumentOrientsTheRing) {
  // Axis +y (the registry default): the ring lies in the xz plane.
  const Torus torus({1, 2, 3}, {0, 1, 0}, 3, 1);
  SurfaceHit hit;
  ASSERT_TRUE(torus.intersect(make_ray({4, 12, 3}, {0, -1, 0}), hit));
  EXPECT_NEAR(hit.t, 9.0, 1e-12);
  expect_vec_near(hit.geometric_normal, {0, 1, 0}, 1e-12);
  EXPECT_FALSE(torus.intersect(make_ray({1, 12, 3}, {0, -1, 0}), hit));  // the hole
  ASSERT_TRUE(torus.intersect(make_ray({1, 2, -10}, {0, 0, 1}), hit));
  EXPECT_NEAR(hit.t, 9.0, 1e-12);
  expect_vec_near(hit.geometric_normal, {0, 0, -1}, 1e-12);
}

TEST(Torus, Bounds) {
  Bounds3 bounds = kRing.bounds();
  expect_vec_near(bounds.lower, {-4, -4, -1}, 1e-15);
  expect_vec_near(bounds.upper, {4, 4, 1}, 1e-15);
  bounds = Torus({1, 2, 3}, {0, 2, 0}, 3, 1).bounds();
  expect_vec_near(bounds.lower, {-3, 1, -1}, 1e-15);
  expect_vec_near(bounds.upper, {5, 3, 7}, 1e-15);
  // Axis (1, 1, 0)/√2: x and y reach 3 sqrt(1/2) + 1, z the full 3 + 1.
  bounds = Torus({0, 0, 0}, {1, 1, 0}, 3, 1).bounds();
  EXPECT_NEAR(bounds.upper.x, 3 * std::sqrt(0.5) + 1, 1e-12);
  EXPECT_NEAR(bounds.upper.z, 4.0, 1e-12);
}

TEST(Torus, SpindleTorusIsAccepted) {
  // r > R: the tube overlaps itself. Along x the outside is at R + r; down the line x = 0.5
  // the first hit is on the tube about (1, 0, 0): (0.5 - 1)^2 + z^2 = 4.
  const Torus spindle({0, 0, 0}, {0, 0, 1}, 1, 2);
  SurfaceHit hit;
  ASSERT_TRUE(spindle.intersect(make_ray({10, 0, 0}, {-1, 0, 0}), hit));
  EXPECT_NEAR(hit.t, 7.0, 1e-12);
  expect_vec_near(hit.geometric_normal, {1, 0, 0}, 1e-12);
  ASSERT_TRUE(spindle.intersect(make_ray({0.5, 0, 10}, {0, 0, -1}), hit));
  EXPECT_NEAR(hit.t, 10 - std::sqrt(3.75), 1e-12);
  expect_vec_near(hit.geometric_normal, Vec3{-0.5, 0, std::sqrt(3.75)} / 2, 1e-12);
}

TEST(Torus, RejectsBadArguments) {
  EXPECT_THROW(Torus({0, 0, 0}, {0, 0, 0}, 3, 1), std::invalid_argument);
  EXPECT_THROW(Torus({0, 0, 0}, {0, 0, 1}, 0, 1), std::invalid_argument);
  EXPECT_THROW(Torus({0, 0, 0}, {0, 0, 1}, 3, 0), std::invalid_argument);
  EXPECT_THROW(Torus({0, 0, 0}, {0, 0, 1}, -3, 1), std::invalid_argument);
  EXPECT_THROW(Torus({0, 0, 0}, {0, 0, 1}, 3, std::nan("")), std::invalid_argument);
  EXPECT_THROW(Torus({0, 0, 0}, {0, 0, 1}, kInfinity, 1), std::invalid_argument);
  EXPECT_THROW(Torus({std::nan(""), 0, 0}, {0, 0, 1}, 3, 1), std::invalid_argument);
}

TEST(Torus, TransformedTorus) {
  // Scaled by 2 (R = 6, r = 2), turned so the axis is +x (rotate 90° about +y: z -> x) and
  // moved to (0, 0, 5).
  const TransformedShape torus(
      std::make_unique<Torus>(Vec3{0, 0, 0}, Vec3{0, 0, 1}, 3.0, 1.0),
      Transform::translate({0, 0, 5}) * Transform::rotate(90, {0, 1, 0}) * Transform::scale({2, 2, 2}));
  SurfaceHit hit;
  ASSERT_TRUE(torus.intersect(make_ray({0, 20, 5}, {0, -1, 0}), hit));
  EXPECT_NEAR(hit.t, 12.0, 1e-12);
  expect_vec_near(hit.geometric_normal, {0, 1, 0}, 1e-12);
  EXPECT_FALSE(torus.intersect(make_ray({20, 0, 5}, {-1, 0, 0}), hit));  // through the hole
  ASSERT_TRUE(torus.intersect(make_ray({20, 6, 5}, {-1, 0, 0}), hit));   // top of the tube
  EXPECT_NEAR(hit.t, 18.0, 1e-12);
  expect_vec_near(hit.geometric_normal, {1, 0, 0}, 1e-12);
  EXPECT_NEAR(torus.bounds().upper.x, 2.0, 1e-12);
  EXPECT_NEAR(torus.bounds().upper.y, 8.0, 1e-12);
}

}  // namespace
}  // namespace candela
