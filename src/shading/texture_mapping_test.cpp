// The mappings of 000 §4.1 (SPEC §7): the sphere's latitude and longitude exactly as the seed
// writes them, at the poles and across the seam; planar, cylindrical and the shape's own uv.
#include "shading/texture_mapping.h"

#include <gtest/gtest.h>

#include <cmath>

#include "geometry/sphere.h"
#include "math/constants.h"

namespace candela {
namespace {

SurfaceHit hit_with_normal(const Vec3& n) {
  SurfaceHit hit;
  hit.geometric_normal = normalize(n);
  hit.shading_normal = hit.geometric_normal;
  hit.position = hit.object_position = hit.geometric_normal;
  return hit;
}

TEST(SphericalMapping, SeedFormulasAtKnownPoints) {
  // Tp = +z (north), Te = +x (the reference point on the equator).
  const SphericalMapping mapping({0, 0, 1}, {1, 0, 0}, nullptr);
  // eq. 4-2, 4-3: v = acos(−Tp·N)/π: 0 at the south pole, 1/2 on the equator, 1 at the north.
  EXPECT_NEAR(mapping.map(hit_with_normal({1, 0, 0})).y, 0.5, 1e-15);
  EXPECT_NEAR(mapping.map(hit_with_normal({1, 0, 0})).x, 0.0, 1e-15);  // Te itself: u = 0
  // A quarter turn toward Tp × Te = +y: u = acos(0)/2π = 1/4.
  EXPECT_NEAR(mapping.map(hit_with_normal({0, 1, 0})).x, 0.25, 1e-15);
  // Opposite Te: u = acos(−1)/2π = 1/2.
  EXPECT_NEAR(mapping.map(hit_with_normal({-1, 0, 0})).x, 0.5, 1e-15);
  // eq. 4-5: the −y side has (Tp × Te)·N < 0, so u := 1 − acos(0)/2π = 3/4.
  EXPECT_NEAR(mapping.map(hit_with_normal({0, -1, 0})).x, 0.75, 1e-15);
  // Latitude 30° north at longitude 60°: φ = 120°, v = 2/3; u = acos(cos 60° sin 120° / sin 120°)/2π.
  const double latitude = kPi / 6, longitude = kPi / 3;
  const Vec3 n{std::cos(latitude) * std::cos(longitude), std::cos(latitude) * std::sin(longitude),
               std::sin(latitude)};
  const Vec2 uv = mapping.map(hit_with_normal(n));
  EXPECT_NEAR(uv.y, 2.0 / 3.0, 1e-12);
  EXPECT_NEAR(uv.x, 1.0 / 6.0, 1e-12);
}

TEST(SphericalMapping, PolesHaveUZero) {
  const SphericalMapping mapping({0, 0, 1}, {1, 0, 0}, nullptr);
  const Vec2 north = mapping.map(hit_with_normal({0, 0, 1}));
  const Vec2 south = mapping.map(hit_with_normal({0, 0, -1}));
  EXPECT_EQ(north.x, 0.0);
  EXPECT_EQ(north.y, 1.0);
  EXPECT_EQ(south.x, 0.0);
  EXPECT_EQ(south.y, 0.0);
  // Next to a pole u is still well defined (finite, in [0, 1]).
  const Vec2 near = mapping.map(hit_with_normal({1e-9, -1e-9, 1}));
  EXPECT_TRUE(std::isfinite(near.x));
  EXPECT_GE(near.x, 0.0);
  EXPECT_LE(near.x, 1.0);
  EXPECT_NEAR(near.y, 1.0, 1e-9);
}

TEST(SphericalMapping, SeamAtTheReferenceMeridian) {
  const SphericalMapping mapping({0, 0, 1}, {1, 0, 0}, nullptr);
  // Just on the +y side of Te u starts at 0; just on the −y side it ends at 1.
  const double small = 1e-6;
  const Vec2 after = mapping.map(hit_with_normal({1, small, 0.3}));
  const Vec2 before = mapping.map(hit_with_normal({1, -small, 0.3}));
  EXPECT_NEAR(after.x, 0.0, 1e-6);
  EXPECT_NEAR(before.x, 1.0, 1e-6);
  EXPECT_NEAR(after.y, before.y, 1e-15);  // the same latitude on both sides
  // u increases monotonically around the equator from Te through Tp × Te.
  double previous = -1;
  for (int i = 0; i < 64; ++i) {
    const double angle = 2 * kPi * (i + 0.5) / 64;
    const double u = mapping.map(hit_with_normal({std::cos(angle), std::sin(angle), 0})).x;
    EXPECT_NEAR(u, (i + 0.5) / 64, 1e-12);
    EXPECT_GT(u, previous);
    previous = u;
  }
}

TEST(SphericalMapping, CentreGivenUsesTheObjectPosition) {
  const Vec3 center{2, 3, 4};
  const SphericalMapping mapping({0, 1, 0}, {0, 0, 1}, &center);
  SurfaceHit hit;
  hit.object_position = center + Vec3{0, 5, 0};  // straight up: the north pole
  hit.geometric_normal = {1, 0, 0};              // ignored when a centre is given
  EXPECT_EQ(mapping.map(hit).y, 1.0);
  // The equator direction is made orthogonal to the pole.
  const SphericalMapping skewed({0, 1, 0}, {0, 0.5, 1}, nullptr);
  EXPECT_NEAR(skewed.map(hit_with_normal({0, 0, 1})).x, 0.0, 1e-15);
}

TEST(SphericalMapping, OnARealSphereHit) {
  // The geometric normal the sphere reports is (p − c)/r, the seed's N.
  const Sphere sphere({1, 2, 3}, 2);
  SurfaceHit hit;
  ASSERT_TRUE(sphere.intersect(Ray{{1, 2, 10}, {0, 0, -1}}, hit));  // hits the +z side
  const SphericalMapping mapping({0, 1, 0}, {0, 0, 1}, nullptr);
  const Vec2 uv = mapping.map(hit);
  EXPECT_NEAR(uv.x, 0.0, 1e-12);
  EXPECT_NEAR(uv.y, 0.5, 1e-12);
}

TEST(SphericalMapping, TurnsWithTheObjectsTransform) {
  // A transformed shape reports its object-space normal too: the mapping reads that one, so
  // the texture turns with the object like every other mapping.
  const SphericalMapping mapping({0, 0, 1}, {1, 0, 0}, nullptr);
  SurfaceHit hit = hit_with_normal({1, 0, 0});  // the world normal
  hit.transformed = true;
  hit.object_normal_ = {0, 0, 1};  // the object's north pole
  EXPECT_EQ(mapping.map(hit).y, 1.0);
}

TEST(SphericalMapping, ScaleAndOffsetApplyAfterTheMapping) {
  const SphericalMapping mapping({0, 0, 1}, {1, 0, 0}, nullptr, UvTransform{{4, 2}, {0.5, 0.25}});
  const Vec2 uv = mapping.map(hit_with_normal({0, 1, 0}));  // raw (1/4, 1/2)
  EXPECT_NEAR(uv.x, 0.25 * 4 + 0.5, 1e-15);
  EXPECT_NEAR(uv.y, 0.5 * 2 + 0.25, 1e-15);
}

TEST(SphericalMapping, RejectsDegenerateAxes) {
  EXPECT_THROW(SphericalMapping({0, 0, 0}, {1, 0, 0}, nullptr), std::invalid_argument);
  EXPECT_THROW(SphericalMapping({0, 0, 1}, {0, 0, 2}, nullptr), std::invalid_argument);
}

TEST(PlanarMapping, ProjectsOntoTheAxes) {
  const PlanarMapping mapping({1, 0, 1}, {0.5, 0, 0}, {0, 0, -2});
  SurfaceHit hit;
  hit.object_position = {3, 7, -1};
  const Vec2 uv = mapping.map(hit);
  EXPECT_DOUBLE_EQ(uv.x, 1.0);  // (3 − 1)·0.5
  EXPECT_DOUBLE_EQ(uv.y, 4.0);  // (−1 − 1)·(−2)
  EXPECT_THROW(PlanarMapping({0, 0, 0}, {1, 0, 0}, {2, 0, 0}), std::invalid_argument);
}

TEST(CylindricalMapping, AngleAndHeight) {
  const CylindricalMapping mapping({0, 1, 0}, {0, 1, 0}, {1, 0, 0}, 4);
  SurfaceHit hit;
  hit.object_position = {1, 1, 0};  // along the reference: u = 0
  EXPECT_NEAR(mapping.map(hit).x, 0.0, 1e-15);
  EXPECT_NEAR(mapping.map(hit).y, 0.0, 1e-15);
  // Counter-clockwise about +y from +x comes axis × reference = y × x = −z.
  hit.object_position = {0, 3, -1};
  EXPECT_NEAR(mapping.map(hit).x, 0.25, 1e-15);
  EXPECT_NEAR(mapping.map(hit).y, 0.5, 1e-15);
  hit.object_position = {0, -1, 1};
  EXPECT_NEAR(mapping.map(hit).x, 0.75, 1e-15);
  EXPECT_NEAR(mapping.map(hit).y, -0.5, 1e-15);
  // Just below the seam u is close to 1, never 1 itself.
  hit.object_position = {1, 1, 1e-12};
  const double u = mapping.map(hit).x;
  EXPECT_LT(u, 1.0);
  EXPECT_GT(u, 0.999);
}

TEST(ParametricMapping, ReadsTheShapesUv) {
  SurfaceHit hit;
  hit.uv = {0.3, 0.8};
  const ParametricMapping mapping(UvTransform{{2, 3}, {0, 1}});
  EXPECT_DOUBLE_EQ(mapping.map(hit).x, 0.6);
  EXPECT_DOUBLE_EQ(mapping.map(hit).y, 3.4);
}

}  // namespace
}  // namespace candela
