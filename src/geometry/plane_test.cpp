#include "geometry/plane.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <memory>

#include "geometry/transformed_shape.h"
#include "math/constants.h"
#include "math/transform.h"
#include "shape_test_support.h"

namespace candela {
namespace {

using candela::testing::make_ray;

TEST(Plane, HitFromEitherSideKeepsTheDeclaredNormal) {
  const Plane plane({0, 0, -5}, {0, 0, 2});  // the normal is normalised
  SurfaceHit hit;
  ASSERT_TRUE(plane.intersect(make_ray({1, 2, 0}, {0, 0, -1}), hit));
  EXPECT_DOUBLE_EQ(hit.t, 5.0);
  EXPECT_NEAR(hit.position.x, 1.0, 1e-12);
  EXPECT_NEAR(hit.position.y, 2.0, 1e-12);
  EXPECT_NEAR(hit.position.z, -5.0, 1e-12);
  EXPECT_EQ(hit.geometric_normal, (Vec3{0, 0, 1}));
  EXPECT_EQ(hit.shading_normal, (Vec3{0, 0, 1}));
  // From below: the same normal, the caller flips it.
  ASSERT_TRUE(plane.intersect(make_ray({0, 0, -10}, {0, 0, 1}), hit));
  EXPECT_DOUBLE_EQ(hit.t, 5.0);
  EXPECT_EQ(hit.geometric_normal, (Vec3{0, 0, 1}));
}

TEST(Plane, ObliqueHit) {
  // The plane x + y + z = 3; the ray from the origin along (1, 1, 1) meets it at (1, 1, 1).
  const Plane plane({3, 0, 0}, {1, 1, 1});
  SurfaceHit hit;
  ASSERT_TRUE(plane.intersect(make_ray({0, 0, 0}, {1, 1, 1}), hit));
  EXPECT_NEAR(hit.t, std::sqrt(3.0), 1e-12);
  EXPECT_NEAR(hit.position.x, 1.0, 1e-12);
  EXPECT_NEAR(hit.position.z, 1.0, 1e-12);
  EXPECT_NEAR(dot(hit.geometric_normal, normalize(Vec3{1, 1, 1})), 1.0, 1e-15);
}

TEST(Plane, ParallelRayMisses) {
  // Grazing convention: N.D = 0 is no intersection (000 §5.6.2), also for a ray in the plane.
  const Plane plane({0, 0, -5}, {0, 0, 1});
  SurfaceHit hit;
  EXPECT_FALSE(plane.intersect(make_ray({0, 0, 0}, {1, 0, 0}), hit));
  EXPECT_FALSE(plane.intersect(make_ray({0, 0, -5}, {1, 1, 0}), hit));
  EXPECT_FALSE(plane.occluded(make_ray({0, 0, -5}, {1, 1, 0})));
}

TEST(Plane, PlaneBehindOriginIsMissed) {
  const Plane plane({0, 0, 5}, {0, 0, 1});
  SurfaceHit hit;
  EXPECT_FALSE(plane.intersect(make_ray({0, 0, 0}, {0, 0, -1}), hit));
  EXPECT_FALSE(plane.occluded(make_ray({0, 0, 0}, {0, 0, -1})));
}

TEST(Plane, RespectsTMinAndTMax) {
  const Plane plane({0, 0, -5}, {0, 0, 1});
  Ray ray = make_ray({0, 0, 0}, {0, 0, -1});
  ray.t_max = 4.9;
  EXPECT_FALSE(plane.occluded(ray));
  ray.t_max = 5.0;  // strict
  EXPECT_FALSE(plane.occluded(ray));
  ray.t_max = 5.1;
  EXPECT_TRUE(plane.occluded(ray));
  ray.t_min = 5.0;
  EXPECT_FALSE(plane.occluded(ray));
}

TEST(Plane, UvAreCoordinatesAlongTheBasis) {
  // orthonormal_basis((0, 0, 1)) gives (1, 0, 0) and (0, 1, 0).
  const Plane plane({1, 2, 3}, {0, 0, 1});
  SurfaceHit hit;
  ASSERT_TRUE(plane.intersect(make_ray({4, 6, 10}, {0, 0, -1}), hit));
  EXPECT_NEAR(hit.uv.x, 3.0, 1e-12);
  EXPECT_NEAR(hit.uv.y, 4.0, 1e-12);
  EXPECT_EQ(hit.dpdu, (Vec3{1, 0, 0}));
  EXPECT_EQ(hit.dpdv, (Vec3{0, 1, 0}));
  // For any normal the basis is orthonormal, in the plane, and dpdu x dpdv = normal.
  const Plane tilted({0, 0, 0}, {1, -2, 3});
  ASSERT_TRUE(tilted.intersect(make_ray({5, 5, 5}, {-1, -1, -2}), hit));  // at (3, 3, 1)
  EXPECT_NEAR(length(hit.dpdu), 1.0, 1e-12);
  EXPECT_NEAR(dot(hit.dpdu, hit.dpdv), 0.0, 1e-12);
  EXPECT_NEAR(dot(cross(hit.dpdu, hit.dpdv), hit.geometric_normal), 1.0, 1e-12);
  EXPECT_NEAR(length(hit.position - Vec3{3, 3, 1}), 0.0, 1e-12);
  // uv reproduce the position: point + u dpdu + v dpdv.
  const Vec3 rebuilt = hit.dpdu * hit.uv.x + hit.dpdv * hit.uv.y;
  EXPECT_NEAR(length(rebuilt - hit.position), 0.0, 1e-12);
}

TEST(Plane, BoundsAreInfinite) {
  const Bounds3 bounds = Plane({0, 0, 0}, {0, 1, 0}).bounds();
  EXPECT_FALSE(bounds.is_finite());
  EXPECT_EQ(bounds.lower.x, -kInfinity);
  EXPECT_EQ(bounds.upper.z, kInfinity);
}

TEST(Plane, RejectsBadArguments) {
  EXPECT_THROW(Plane({0, 0, 0}, {0, 0, 0}), std::invalid_argument);
  EXPECT_THROW(Plane({0, 0, 0}, {0, std::nan(""), 1}), std::invalid_argument);
  EXPECT_THROW(Plane({0, 0, 0}, {kInfinity, 0, 0}), std::invalid_argument);
  EXPECT_THROW(Plane({kInfinity, 0, 0}, {0, 0, 1}), std::invalid_argument);
}

TEST(Plane, TransformedPlane) {
  // z = 0 rotated 90° about +x (z -> -y) and moved to y = 3: the plane y = 3 facing -y.
  const TransformedShape plane(std::make_unique<Plane>(Vec3{0, 0, 0}, Vec3{0, 0, 1}),
                               Transform::translate({0, 3, 0}) * Transform::rotate(90, {1, 0, 0}));
  SurfaceHit hit;
  ASSERT_TRUE(plane.intersect(make_ray({2, 10, 1}, {0, -1, 0}), hit));
  EXPECT_NEAR(hit.t, 7.0, 1e-12);
  EXPECT_NEAR(hit.position.y, 3.0, 1e-12);
  EXPECT_NEAR(hit.geometric_normal.y, -1.0, 1e-12);
  EXPECT_FALSE(plane.intersect(make_ray({2, 10, 1}, {1, 0, 0}), hit));
}

// hit_distance (what the accelerators ask of every plane on every ray) is intersect's t bit for
// bit, and false exactly when intersect is; a transformed plane answers through the default.
TEST(Plane, HitDistanceIsIntersectsDistance) {
  const Plane plane({0.3, -0.2, 0.7}, {0.2, 1, -0.4});
  const TransformedShape moved(std::make_unique<Plane>(Vec3{0, 0, 0}, Vec3{0, 0, 1}),
                               Transform::rotate(30, {1, 1, 0}) * Transform::translate({0, 0, 0.5}));
  int hits = 0;
  for (int i = 0; i < 400; ++i) {
    const double a = 0.37 * i, b = 0.11 * i;
    Ray ray = make_ray({std::sin(a) * 3, std::cos(b) * 2, std::sin(a + b)},
                       {std::cos(a) * std::sin(b), std::sin(a) * std::sin(b), std::cos(b)});
    ray.t_min = (i % 3) * 0.25;
    ray.t_max = i % 5 ? kInfinity : 2.0;
    for (const Shape* shape : {static_cast<const Shape*>(&plane), static_cast<const Shape*>(&moved)}) {
      SurfaceHit hit;
      double t = -1;
      const bool intersected = shape->intersect(ray, hit);
      ASSERT_EQ(shape->hit_distance(ray, t), intersected) << i;
      if (!intersected) continue;
      ++hits;
      EXPECT_EQ(std::bit_cast<uint64_t>(t), std::bit_cast<uint64_t>(hit.t)) << i;
    }
  }
  EXPECT_GT(hits, 200);
}

}  // namespace
}  // namespace candela
