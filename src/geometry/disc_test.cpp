#include "geometry/disc.h"

#include <gtest/gtest.h>

#include <cmath>

#include "geometry/transformed_shape.h"
#include "math/constants.h"
#include "math/transform.h"
#include "shape_test_support.h"

namespace candela {
namespace {

using candela::testing::make_ray;

TEST(Disc, HitInsideTheRadius) {
  // orthonormal_basis((0, 0, 1)) = (1, 0, 0), (0, 1, 0): u is the angle from +x about +z.
  const Disc disc({0, 0, 0}, {0, 0, 3}, 2);
  SurfaceHit hit;
  ASSERT_TRUE(disc.intersect(make_ray({1, 0, 5}, {0, 0, -1}), hit));
  EXPECT_DOUBLE_EQ(hit.t, 5.0);
  EXPECT_NEAR(hit.position.x, 1.0, 1e-12);
  EXPECT_EQ(hit.geometric_normal, (Vec3{0, 0, 1}));
  EXPECT_NEAR(hit.uv.x, 0.0, 1e-12);
  EXPECT_NEAR(hit.uv.y, 0.5, 1e-12);  // (radius - r) / radius = (2 - 1) / 2
  ASSERT_TRUE(disc.intersect(make_ray({0, 1.5, 5}, {0, 0, -1}), hit));
  EXPECT_NEAR(hit.uv.x, 0.25, 1e-12);
  EXPECT_NEAR(hit.uv.y, 0.25, 1e-12);
  // From below: the declared normal is kept.
  ASSERT_TRUE(disc.intersect(make_ray({-1, -1, -2}, {0, 0, 1}), hit));
  EXPECT_DOUBLE_EQ(hit.t, 2.0);
  EXPECT_EQ(hit.geometric_normal, (Vec3{0, 0, 1}));
  EXPECT_NEAR(hit.uv.x, 0.625, 1e-12);  // 225°
}

TEST(Disc, MissOutsideTheRadius) {
  const Disc disc({0, 0, 0}, {0, 0, 1}, 2);
  SurfaceHit hit;
  EXPECT_FALSE(disc.intersect(make_ray({1.5, 1.5, 5}, {0, 0, -1}), hit));  // r = 2.12
  EXPECT_FALSE(disc.occluded(make_ray({0, -2.5, 5}, {0, 0, -1})));
}

TEST(Disc, RimIsIncludedAndParallelRaysMiss) {
  // Grazing convention: the disc is closed (r = radius hits); a ray parallel to it misses.
  const Disc disc({0, 0, 0}, {0, 0, 1}, 2);
  SurfaceHit hit;
  ASSERT_TRUE(disc.intersect(make_ray({2, 0, 5}, {0, 0, -1}), hit));
  EXPECT_NEAR(hit.uv.y, 0.0, 1e-12);
  EXPECT_FALSE(disc.intersect(make_ray({2 + 1e-9, 0, 5}, {0, 0, -1}), hit));
  EXPECT_FALSE(disc.intersect(make_ray({-5, 0, 0}, {1, 0, 0}), hit));
  EXPECT_FALSE(disc.intersect(make_ray({-5, 0, 1}, {1, 0, 0}), hit));
}

TEST(Disc, AnnulusHasAHole) {
  const Disc annulus({0, 0, 0}, {0, 0, 1}, 2, 1);
  SurfaceHit hit;
  EXPECT_FALSE(annulus.intersect(make_ray({0.5, 0, 5}, {0, 0, -1}), hit));
  EXPECT_FALSE(annulus.intersect(make_ray({0, 0, 5}, {0, 0, -1}), hit));
  ASSERT_TRUE(annulus.intersect(make_ray({1, 0, 5}, {0, 0, -1}), hit));  // inner rim hits
  EXPECT_NEAR(hit.uv.y, 1.0, 1e-12);
  ASSERT_TRUE(annulus.intersect(make_ray({-1.5, 0, 5}, {0, 0, -1}), hit));
  EXPECT_NEAR(hit.uv.x, 0.5, 1e-12);
  EXPECT_NEAR(hit.uv.y, 0.5, 1e-12);  // (2 - 1.5) / (2 - 1)
}

TEST(Disc, BehindOriginAndTMax) {
  const Disc disc({0, 0, -5}, {0, 0, 1}, 1);
  SurfaceHit hit;
  EXPECT_FALSE(disc.intersect(make_ray({0, 0, 0}, {0, 0, 1}), hit));
  Ray ray = make_ray({0, 0, 0}, {0, 0, -1});
  ray.t_max = 5.0;
  EXPECT_FALSE(disc.occluded(ray));
  ray.t_max = 5.01;
  EXPECT_TRUE(disc.occluded(ray));
}

TEST(Disc, DerivativesFollowTheNormal) {
  const Disc disc({1, 2, 3}, {1, 1, 1}, 2, 0.5);
  const Vec3 n = normalize(Vec3{1, 1, 1});
  const Vec3 in_plane = normalize(Vec3{1, -1, 0});
  const Vec3 target = Vec3{1, 2, 3} + in_plane * 1.25;  // r = 1.25
  SurfaceHit hit;
  ASSERT_TRUE(disc.intersect(make_ray(target + n * 4, -n), hit));
  EXPECT_NEAR(hit.t, 4.0, 1e-12);
  EXPECT_NEAR(hit.uv.y, 0.5, 1e-12);  // (2 - 1.25) / 1.5
  EXPECT_NEAR(dot(hit.geometric_normal, n), 1.0, 1e-15);
  EXPECT_NEAR(dot(hit.dpdu, n), 0.0, 1e-12);
  EXPECT_NEAR(dot(hit.dpdv, n), 0.0, 1e-12);
  EXPECT_NEAR(length(hit.dpdu), 2 * kPi * 1.25, 1e-12);
  EXPECT_NEAR(length(hit.dpdv), 1.5, 1e-12);
  EXPECT_GT(dot(cross(hit.dpdu, hit.dpdv), n), 0);
}

TEST(Disc, Bounds) {
  Bounds3 bounds = Disc({1, 2, 3}, {0, 0, 1}, 2).bounds();
  EXPECT_EQ(bounds.lower, (Vec3{-1, 0, 3}));
  EXPECT_EQ(bounds.upper, (Vec3{3, 4, 3}));
  // Normal (1, 0, 1)/√2: x and z reach 2 sqrt(1 - 1/2) = √2, y the full radius.
  bounds = Disc({0, 0, 0}, {1, 0, 1}, 2).bounds();
  EXPECT_NEAR(bounds.upper.x, std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(bounds.upper.y, 2.0, 1e-12);
  EXPECT_NEAR(bounds.lower.z, -std::sqrt(2.0), 1e-12);
}

TEST(Disc, RejectsBadArguments) {
  EXPECT_THROW(Disc({0, 0, 0}, {0, 0, 1}, 0), std::invalid_argument);
  EXPECT_THROW(Disc({0, 0, 0}, {0, 0, 1}, -1), std::invalid_argument);
  EXPECT_THROW(Disc({0, 0, 0}, {0, 0, 1}, std::nan("")), std::invalid_argument);
  EXPECT_THROW(Disc({0, 0, 0}, {0, 0, 1}, kInfinity), std::invalid_argument);
  EXPECT_THROW(Disc({0, 0, 0}, {0, 0, 0}, 1), std::invalid_argument);
  EXPECT_THROW(Disc({0, 0, 0}, {0, 0, 1}, 1, -0.5), std::invalid_argument);
  EXPECT_THROW(Disc({0, 0, 0}, {0, 0, 1}, 1, 1), std::invalid_argument);
  EXPECT_THROW(Disc({0, 0, 0}, {0, 0, 1}, 1, std::nan("")), std::invalid_argument);
  EXPECT_THROW(Disc({0, std::nan(""), 0}, {0, 0, 1}, 1), std::invalid_argument);
}

TEST(Disc, TransformedDiscIsAnEllipse) {
  // The unit disc scaled by (2, 1, 1) and moved to z = -3: the ellipse x²/4 + y² <= 1.
  const TransformedShape ellipse(std::make_unique<Disc>(Vec3{0, 0, 0}, Vec3{0, 0, 1}, 1.0),
                                 Transform::translate({0, 0, -3}) * Transform::scale({2, 1, 1}));
  SurfaceHit hit;
  ASSERT_TRUE(ellipse.intersect(make_ray({1.9, 0, 0}, {0, 0, -1}), hit));
  EXPECT_NEAR(hit.t, 3.0, 1e-12);
  EXPECT_NEAR(hit.geometric_normal.z, 1.0, 1e-12);
  EXPECT_FALSE(ellipse.intersect(make_ray({2.1, 0, 0}, {0, 0, -1}), hit));
  EXPECT_FALSE(ellipse.intersect(make_ray({0, 1.1, 0}, {0, 0, -1}), hit));
  EXPECT_NEAR(ellipse.bounds().upper.x, 2.0, 1e-12);
}

}  // namespace
}  // namespace candela
