#include "geometry/cone.h"

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

// Base radius 1 at z = 0, apex at z = 2: radius(z) = 1 - z/2, slope k = -1/2, so the outward
// side normal at angle φ is (cos φ, sin φ, 1/2) / sqrt(5/4) = (2 cos φ, 2 sin φ, 1) / √5.
const Cone kPointed({0, 0, 0}, 1, {0, 0, 2}, 0);
const Cone kOpenPointed({0, 0, 0}, 1, {0, 0, 2}, 0, false);
const Vec3 kSideNormalX = Vec3{2, 0, 1} / std::sqrt(5.0);

TEST(Cone, SideHit) {
  SurfaceHit hit;
  ASSERT_TRUE(kPointed.intersect(make_ray({5, 0, 0.5}, {-1, 0, 0}), hit));  // radius 0.75
  EXPECT_NEAR(hit.t, 4.25, 1e-12);
  expect_vec_near(hit.position, {0.75, 0, 0.5}, 1e-12);
  expect_vec_near(hit.geometric_normal, kSideNormalX, 1e-12);
  EXPECT_NEAR(hit.uv.x, 0.0, 1e-12);
  EXPECT_NEAR(hit.uv.y, 0.25, 1e-12);
  EXPECT_GT(dot(cross(hit.dpdu, hit.dpdv), hit.geometric_normal), 0);
  // dp/dv runs along the side from the base rim to the apex: height * (k cos φ, k sin φ, 1).
  expect_vec_near(hit.dpdv, {-1, 0, 2}, 1e-12);
  ASSERT_TRUE(kPointed.intersect(make_ray({0, -5, 1}, {0, 1, 0}), hit));  // radius 0.5
  EXPECT_NEAR(hit.t, 4.5, 1e-12);
  expect_vec_near(hit.geometric_normal, Vec3{0, -2, 1} / std::sqrt(5.0), 1e-12);
  EXPECT_NEAR(hit.uv.x, 0.75, 1e-12);
}

TEST(Cone, BaseCap) {
  SurfaceHit hit;
  ASSERT_TRUE(kPointed.intersect(make_ray({0.5, 0, -5}, {0, 0, 1}), hit));
  EXPECT_DOUBLE_EQ(hit.t, 5.0);
  expect_vec_near(hit.geometric_normal, {0, 0, -1}, 1e-15);
  EXPECT_NEAR(hit.uv.y, 0.5, 1e-12);
  EXPECT_GT(dot(cross(hit.dpdu, hit.dpdv), hit.geometric_normal), 0);
}

TEST(Cone, OriginInsideHitsTheFarSurface) {
  SurfaceHit hit;
  ASSERT_TRUE(kPointed.intersect(make_ray({0, 0, 0.5}, {1, 0, 0}), hit));
  EXPECT_NEAR(hit.t, 0.75, 1e-12);
  expect_vec_near(hit.geometric_normal, kSideNormalX, 1e-12);
  ASSERT_TRUE(kPointed.intersect(make_ray({0, 0, 0.5}, {0, 0, -1}), hit));
  EXPECT_DOUBLE_EQ(hit.t, 0.5);
  expect_vec_near(hit.geometric_normal, {0, 0, -1}, 1e-15);
  // Up the axis: leaves through the apex (a double root), normal along +axis.
  ASSERT_TRUE(kPointed.intersect(make_ray({0, 0, 0.5}, {0, 0, 1}), hit));
  EXPECT_NEAR(hit.t, 1.5, 1e-12);
  expect_vec_near(hit.geometric_normal, {0, 0, 1}, 1e-12);
}

TEST(Cone, RayParallelToAGenerator) {
  // Direction (1, 0, 2) is parallel to the generator from (-1, 0, 0) to the apex: the quadratic
  // has a = 0 and a single root. From (0, 0, 0.5): x = u, z = 0.5 + 2u meets the side
  // x = 1 - z/2 at u = 0.375, i.e. (0.375, 0, 1.25), t = 0.375 √5.
  SurfaceHit hit;
  ASSERT_TRUE(kPointed.intersect(make_ray({0, 0, 0.5}, {1, 0, 2}), hit));
  EXPECT_NEAR(hit.t, 0.375 * std::sqrt(5.0), 1e-12);
  expect_vec_near(hit.position, {0.375, 0, 1.25}, 1e-12);
  expect_vec_near(hit.geometric_normal, kSideNormalX, 1e-12);
  // The same direction from outside, beside the cone: it passes the -x side and misses.
  EXPECT_FALSE(kPointed.intersect(make_ray({-1.5, 0, 0}, {1, 0, 2}), hit));
}

TEST(Cone, TangentRayCountsAsHit) {
  // Grazing convention: a zero discriminant is a hit. The line y-ward through (0.75, 0, 0.5)
  // touches the side there (radius 0.75 at z = 0.5).
  SurfaceHit hit;
  ASSERT_TRUE(kPointed.intersect(make_ray({0.75, -5, 0.5}, {0, 1, 0}), hit));
  EXPECT_DOUBLE_EQ(hit.t, 5.0);
  expect_vec_near(hit.geometric_normal, kSideNormalX, 1e-12);
  EXPECT_FALSE(kPointed.intersect(make_ray({0.76, -5, 0.5}, {0, 1, 0}), hit));
}

TEST(Cone, Misses) {
  SurfaceHit hit;
  EXPECT_FALSE(kPointed.intersect(make_ray({5, 0, 2.5}, {-1, 0, 0}), hit));  // above the apex
  EXPECT_FALSE(kPointed.intersect(make_ray({5, 0, -0.5}, {-1, 0, 0}), hit));
  EXPECT_FALSE(kPointed.intersect(make_ray({5, 0.9, 1}, {-1, 0, 0}), hit));  // radius 0.5
  EXPECT_FALSE(kPointed.intersect(make_ray({5, 0, 0.5}, {1, 0, 0}), hit));   // behind
  // The other nappe of the double cone (above the apex) is not part of the shape.
  EXPECT_FALSE(kPointed.intersect(make_ray({5, 0, 3}, {-1, 0, 0}), hit));
  EXPECT_FALSE(kPointed.occluded(make_ray({0, 0, 5}, {0, 0, 1})));
}

TEST(Cone, OpenConeShowsItsInside) {
  // Up through the open base: the inside of the side where the radius is 0.5, z = 1.
  SurfaceHit hit;
  ASSERT_TRUE(kOpenPointed.intersect(make_ray({0.5, 0, -5}, {0, 0, 1}), hit));
  EXPECT_NEAR(hit.t, 6.0, 1e-12);
  expect_vec_near(hit.geometric_normal, kSideNormalX, 1e-12);
}

TEST(Cone, TruncatedConeHasTwoCaps) {
  const Cone frustum({0, 0, 0}, 2, {0, 0, 2}, 1);  // k = -1/2 again
  SurfaceHit hit;
  ASSERT_TRUE(frustum.intersect(make_ray({0.5, 0, 5}, {0, 0, -1}), hit));
  EXPECT_DOUBLE_EQ(hit.t, 3.0);
  expect_vec_near(hit.geometric_normal, {0, 0, 1}, 1e-15);
  EXPECT_NEAR(hit.uv.y, 0.5, 1e-12);  // 1 - r / cap radius
  // Radius 1.5 at z = 1.
  ASSERT_TRUE(frustum.intersect(make_ray({5, 0, 1}, {-1, 0, 0}), hit));
  EXPECT_NEAR(hit.t, 3.5, 1e-12);
  expect_vec_near(hit.geometric_normal, kSideNormalX, 1e-12);
  ASSERT_TRUE(frustum.intersect(make_ray({1.5, 0, -5}, {0, 0, 1}), hit));
  EXPECT_DOUBLE_EQ(hit.t, 5.0);
  expect_vec_near(hit.geometric_normal, {0, 0, -1}, 1e-15);
  // Widening cone, apex at the base: k = 1, normal (cos φ, sin φ, -1) / √2.
  const Cone widening({0, 0, 0}, 0, {0, 0, 1}, 1);
  ASSERT_TRUE(widening.intersect(make_ray({5, 0, 0.5}, {-1, 0, 0}), hit));
  EXPECT_NEAR(hit.t, 4.5, 1e-12);
  expect_vec_near(hit.geometric_normal, Vec3{1, 0, -1} / std::sqrt(2.0), 1e-12);
  ASSERT_TRUE(widening.intersect(make_ray({0, 0, 0.5}, {0, 0, -1}), hit));  // the apex
  EXPECT_NEAR(hit.t, 0.5, 1e-12);
  expect_vec_near(hit.geometric_normal, {0, 0, -1}, 1e-12);
}

TEST(Cone, RespectsTMinAndTMax) {
  Ray ray = make_ray({5, 0, 0.5}, {-1, 0, 0});
  ray.t_max = 4.25;
  EXPECT_FALSE(kPointed.occluded(ray));
  ray.t_max = 4.26;
  EXPECT_TRUE(kPointed.occluded(ray));
  ray.t_max = kInfinity;
  ray.t_min = 4.3;
  SurfaceHit hit;
  ASSERT_TRUE(kPointed.intersect(ray, hit));
  EXPECT_NEAR(hit.t, 5.75, 1e-12);
  expect_vec_near(hit.geometric_normal, Vec3{-2, 0, 1} / std::sqrt(5.0), 1e-12);
}

TEST(Cone, Bounds) {
  Bounds3 bounds = kPointed.bounds();
  expect_vec_near(bounds.lower, {-1, -1, 0}, 1e-15);
  expect_vec_near(bounds.upper, {1, 1, 2}, 1e-15);
  // Axis along (3, 4, 0), radius 1 at the base, 2 at the cap (3, 4, 0).
  bounds = Cone({0, 0, 0}, 1, {3, 4, 0}, 2).bounds();
  expect_vec_near(bounds.lower, {-0.8, -0.6, -2}, 1e-12);
  expect_vec_near(bounds.upper, {3 + 1.6, 4 + 1.2, 2}, 1e-12);
}

TEST(Cone, RejectsBadArguments) {
  EXPECT_THROW(Cone({0, 0, 0}, 0, {0, 0, 1}, 0), std::invalid_argument);
  EXPECT_THROW(Cone({0, 0, 0}, -1, {0, 0, 1}, 1), std::invalid_argument);
  EXPECT_THROW(Cone({0, 0, 0}, 1, {0, 0, 1}, -0.5), std::invalid_argument);
  EXPECT_THROW(Cone({0, 0, 0}, std::nan(""), {0, 0, 1}, 1), std::invalid_argument);
  EXPECT_THROW(Cone({0, 0, 0}, 1, {0, 0, 1}, kInfinity), std::invalid_argument);
  EXPECT_THROW(Cone({1, 1, 1}, 1, {1, 1, 1}, 0), std::invalid_argument);
  EXPECT_NO_THROW(Cone({0, 0, 0}, 1, {0, 0, 1}, 1));  // a cylinder
}

TEST(Cone, TransformedLyingCone) {
  // Rotated 90° about +y (z -> x, x -> -z) and moved to (10, 0, 0): the axis runs from x = 10
  // to x = 12. Down -y at x = 10.5 the radius is 0.75; the local normal (0, 2, 1)/√5 turns
  // into (1, 2, 0)/√5.
  const TransformedShape cone(std::make_unique<Cone>(Vec3{0, 0, 0}, 1.0, Vec3{0, 0, 2}, 0.0),
                              Transform::translate({10, 0, 0}) * Transform::rotate(90, {0, 1, 0}));
  SurfaceHit hit;
  ASSERT_TRUE(cone.intersect(make_ray({10.5, 5, 0}, {0, -1, 0}), hit));
  EXPECT_NEAR(hit.t, 4.25, 1e-12);
  expect_vec_near(hit.geometric_normal, Vec3{1, 2, 0} / std::sqrt(5.0), 1e-12);
  ASSERT_TRUE(cone.intersect(make_ray({5, 0.5, 0}, {1, 0, 0}), hit));  // the base cap
  EXPECT_NEAR(hit.t, 5.0, 1e-12);
  expect_vec_near(hit.geometric_normal, {-1, 0, 0}, 1e-12);
  const Bounds3 bounds = cone.bounds();
  EXPECT_NEAR(bounds.lower.x, 10.0, 1e-12);
  EXPECT_NEAR(bounds.upper.x, 12.0, 1e-12);
}

}  // namespace
}  // namespace candela
