#include "geometry/quad.h"

#include <gtest/gtest.h>

#include <cmath>

#include "shape_test_support.h"

namespace candela {
namespace {

using candela::testing::expect_vec_near;
using candela::testing::make_ray;

TEST(Quad, ParametricUvOfASkewedParallelogram) {
  // corner (1, 0, 0), edges (2, 0, 0) and (1, 1, 0): the point u = 0.25, v = 0.5 is
  // (1 + 0.5 + 0.5, 0.5, 0) = (2, 0.5, 0).
  const Quad quad({1, 0, 0}, {2, 0, 0}, {1, 1, 0});
  SurfaceHit hit;
  ASSERT_TRUE(quad.intersect(make_ray({2, 0.5, 3}, {0, 0, -1}), hit));
  EXPECT_DOUBLE_EQ(hit.t, 3.0);
  EXPECT_NEAR(hit.uv.x, 0.25, 1e-15);
  EXPECT_NEAR(hit.uv.y, 0.5, 1e-15);
  expect_vec_near(hit.dpdu, {2, 0, 0}, 0);
  expect_vec_near(hit.dpdv, {1, 1, 0}, 0);
  expect_vec_near(hit.geometric_normal, {0, 0, 1}, 1e-15);  // edge_u × edge_v
  EXPECT_NEAR(quad.area(), 2.0, 1e-15);
  // Inside the bounding rectangle but outside the slanted edge: a polygon's bounding-box uv
  // would not tell these apart, the parametric test does.
  EXPECT_FALSE(quad.intersect(make_ray({1.2, 0.9, 3}, {0, 0, -1}), hit));
  EXPECT_TRUE(quad.occluded(make_ray({3.5, 0.9, 3}, {0, 0, -1})));
}

TEST(Quad, EdgesAndCornersBelongToTheQuadBothSidesHit) {
  const Quad quad({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  SurfaceHit hit;
  for (const Vec3& p : {Vec3{0, 0, 0}, Vec3{1, 1, 0}, Vec3{0.5, 0, 0}, Vec3{1, 0.5, 0}}) {
    EXPECT_TRUE(quad.intersect(make_ray(p + Vec3{0, 0, 2}, {0, 0, -1}), hit)) << p;
    EXPECT_TRUE(quad.intersect(make_ray(p - Vec3{0, 0, 2}, {0, 0, 1}), hit)) << p;
    EXPECT_EQ(hit.geometric_normal, (Vec3{0, 0, 1}));  // the declared side, from below too
  }
  EXPECT_FALSE(quad.intersect(make_ray({1.0000001, 0.5, 2}, {0, 0, -1}), hit));
  // In the plane: a miss; outside (t_min, t_max): a miss.
  EXPECT_FALSE(quad.intersect(make_ray({-1, 0.5, 0}, {1, 0, 0}), hit));
  EXPECT_FALSE(quad.intersect(Ray{{0.5, 0.5, 2}, {0, 0, -1}, 0, 1.5}, hit));
}

TEST(Quad, BoundsAndErrors) {
  const Quad quad({1, 2, 3}, {1, 0, 1}, {0, 2, 0});
  const Bounds3 b = quad.bounds();
  expect_vec_near(b.lower, {1, 2, 3}, 0);
  expect_vec_near(b.upper, {2, 4, 4}, 0);
  EXPECT_THROW(Quad({0, 0, 0}, {1, 0, 0}, {2, 0, 0}), std::invalid_argument);
  EXPECT_THROW(Quad({0, 0, 0}, {0, 0, 0}, {0, 1, 0}), std::invalid_argument);
  EXPECT_THROW(Quad({0, NAN, 0}, {1, 0, 0}, {0, 1, 0}), std::invalid_argument);
}

}  // namespace
}  // namespace candela
