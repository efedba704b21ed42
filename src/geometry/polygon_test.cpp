#include "geometry/polygon.h"

#include <gtest/gtest.h>

#include <cmath>

#include "geometry/transformed_shape.h"
#include "math/constants.h"
#include "math/transform.h"
#include "shape_test_support.h"

namespace candela {
namespace {

using candela::testing::make_ray;

// A ray straight down onto z = 0 at (x, y).
Ray down_at(double x, double y) {
  return make_ray({x, y, 5}, {0, 0, -1});
}

Polygon unit_square() {
  return Polygon({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
}

// The L of 000-style tests: the 2x2 square without its upper right quarter (the notch).
Polygon l_shape() {
  return Polygon({{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}, {1, 2, 0}, {0, 2, 0}});
}

TEST(Polygon, HitInsideASquare) {
  const Polygon square = unit_square();
  SurfaceHit hit;
  ASSERT_TRUE(square.intersect(down_at(0.25, 0.5), hit));
  EXPECT_DOUBLE_EQ(hit.t, 5.0);
  EXPECT_NEAR(hit.position.x, 0.25, 1e-12);
  EXPECT_NEAR(hit.position.z, 0.0, 1e-12);
  EXPECT_EQ(hit.geometric_normal, (Vec3{0, 0, 1}));  // counter-clockwise seen from +z
  EXPECT_NEAR(hit.uv.x, 0.25, 1e-12);
  EXPECT_NEAR(hit.uv.y, 0.5, 1e-12);
  EXPECT_NEAR(length(hit.dpdu - Vec3{1, 0, 0}), 0.0, 1e-12);
  EXPECT_NEAR(length(hit.dpdv - Vec3{0, 1, 0}), 0.0, 1e-12);
  EXPECT_FALSE(square.intersect(down_at(1.5, 0.5), hit));
  EXPECT_FALSE(square.intersect(down_at(0.5, -0.5), hit));
}

TEST(Polygon, NormalFollowsTheVertexOrder) {
  const Polygon clockwise({{0, 0, 0}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}});
  SurfaceHit hit;
  ASSERT_TRUE(clockwise.intersect(down_at(0.5, 0.5), hit));
  EXPECT_EQ(hit.geometric_normal, (Vec3{0, 0, -1}));  // both sides hit, not flipped
  EXPECT_GT(dot(cross(hit.dpdu, hit.dpdv), hit.geometric_normal), 0);
}

TEST(Polygon, ObliquePlaneHit) {
  // The triangle x + y + z = 1 in the positive octant: the ray along (1, 1, 1) meets it at
  // (1/3, 1/3, 1/3), t = 1/√3.
  const Polygon triangle({{1, 0, 0}, {0, 1, 0}, {0, 0, 1}});
  SurfaceHit hit;
  ASSERT_TRUE(triangle.intersect(make_ray({0, 0, 0}, {1, 1, 1}), hit));
  EXPECT_NEAR(hit.t, 1 / std::sqrt(3.0), 1e-12);
  EXPECT_NEAR(dot(hit.geometric_normal, normalize(Vec3{1, 1, 1})), 1.0, 1e-12);
  EXPECT_FALSE(triangle.intersect(make_ray({0, 0, 0}, {1, 1, -0.1}), hit));
}

TEST(Polygon, ConcaveLShape) {
  const Polygon l = l_shape();
  EXPECT_TRUE(l.occluded(down_at(0.5, 0.5)));
  EXPECT_TRUE(l.occluded(down_at(1.5, 0.5)));
  EXPECT_TRUE(l.occluded(down_at(0.5, 1.5)));
  EXPECT_FALSE(l.occluded(down_at(1.5, 1.5)));  // in the notch
  EXPECT_FALSE(l.occluded(down_at(1.1, 1.9)));  // in the notch
  EXPECT_FALSE(l.occluded(down_at(2.5, 0.5)));
  EXPECT_FALSE(l.occluded(down_at(-0.5, 1.5)));
  // The +u half-axis from (0.5, 1) runs along the edge (2,1)-(1,1) through two vertices.
  EXPECT_TRUE(l.occluded(down_at(0.5, 1.0)));
  EXPECT_FALSE(l.occluded(down_at(-0.5, 1.0)));
}

TEST(Polygon, VertexOnTheHalfAxisCountsOnThePlusVSide) {
  // 000 §5.6.2: a diamond with vertices at v = 0. From (±0.5, 0) the +u half-axis passes
  // through the vertex (1, 0); from (-1.5, 0) through both (-1, 0) and (1, 0). Counting a
  // vertex twice (or not at all) would get these wrong.
  const Polygon diamond({{1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}});
  EXPECT_TRUE(diamond.occluded(down_at(0.5, 0)));
  EXPECT_TRUE(diamond.occluded(down_at(-0.5, 0)));
  EXPECT_TRUE(diamond.occluded(down_at(0, 0)));
  EXPECT_FALSE(diamond.occluded(down_at(-1.5, 0)));
  EXPECT_FALSE(diamond.occluded(down_at(1.5, 0)));
  EXPECT_TRUE(diamond.occluded(down_at(0, 0.5)));
  EXPECT_FALSE(diamond.occluded(down_at(0, 1.5)));
  // The same diamond in the plane y = 0 (projection onto xz: u = z, v = x), so the half-axis
  // from (x = 0, z) passes through the vertices (0, 0, ±1).
  const Polygon upright({{1, 0, 0}, {0, 0, 1}, {-1, 0, 0}, {0, 0, -1}});
  const auto across = [](double x, double z) { return make_ray({x, -5, z}, {0, 1, 0}); };
  EXPECT_TRUE(upright.occluded(across(0, 0.5)));
  EXPECT_TRUE(upright.occluded(across(0, -0.5)));
  EXPECT_FALSE(upright.occluded(across(0, 1.5)));
  EXPECT_FALSE(upright.occluded(across(0, -1.5)));
  EXPECT_TRUE(upright.occluded(across(0.5, 0)));
  EXPECT_FALSE(upright.occluded(across(1.5, 0)));
}

TEST(Polygon, ConcaveStar) {
  // A five-pointed star (10 vertices, outer radius 2, inner radius 0.8) in the plane x = 1:
  // the centre and the points of the star are inside, the gaps between points outside.
  std::vector<Vec3> vertices;
  for (int i = 0; i < 10; ++i) {
    const double angle = i * kPi / 5;
    const double radius = i % 2 == 0 ? 2.0 : 0.8;
    vertices.push_back({1, radius * std::cos(angle), radius * std::sin(angle)});
  }
  const Polygon star(vertices);
  const auto along_x = [](double angle, double radius) {
    return make_ray({-5, radius * std::cos(angle), radius * std::sin(angle)}, {1, 0, 0});
  };
  SurfaceHit hit;
  ASSERT_TRUE(star.intersect(along_x(0, 0), hit));
  EXPECT_NEAR(hit.t, 6.0, 1e-12);
  for (int i = 0; i < 5; ++i) {
    const double point = 2 * i * kPi / 5, gap = point + kPi / 5;
    EXPECT_TRUE(star.occluded(along_x(point, 1.5))) << i;   // inside a point of the star
    EXPECT_FALSE(star.occluded(along_x(gap, 1.0))) << i;    // between two points
    EXPECT_TRUE(star.occluded(along_x(gap, 0.6))) << i;     // the pentagon in the middle
    EXPECT_FALSE(star.occluded(along_x(point, 2.1))) << i;  // beyond the tip
  }
}

TEST(Polygon, SharedEdgesAndVerticesBelongToOnePolygon) {
  // Grazing convention: the crossing rule makes the polygon half-open, so four squares
  // meeting at (1, 1) cover every point of their shared edges and corner exactly once.
  const Polygon squares[4] = {
      Polygon({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}),
      Polygon({{1, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}}),
      Polygon({{0, 1, 0}, {1, 1, 0}, {1, 2, 0}, {0, 2, 0}}),
      Polygon({{1, 1, 0}, {2, 1, 0}, {2, 2, 0}, {1, 2, 0}}),
  };
  const Vec2 points[5] = {{1, 0.5}, {1, 1.5}, {0.5, 1}, {1.5, 1}, {1, 1}};
  for (const Vec2& point : points) {
    int hits = 0;
    for (const Polygon& square : squares) hits += square.occluded(down_at(point.x, point.y));
    EXPECT_EQ(hits, 1) << point.x << ", " << point.y;
  }
}

TEST(Polygon, ParallelBehindAndTMax) {
  const Polygon square = unit_square();
  SurfaceHit hit;
  EXPECT_FALSE(square.intersect(make_ray({-1, 0.5, 0}, {1, 0, 0}), hit));  // in its plane
  EXPECT_FALSE(square.intersect(make_ray({0.5, 0.5, 1}, {1, 0, 0}), hit));
  EXPECT_FALSE(square.intersect(make_ray({0.5, 0.5, 1}, {0, 0, 1}), hit));  // behind
  Ray ray = down_at(0.5, 0.5);
  ray.t_max = 5.0;
  EXPECT_FALSE(square.occluded(ray));
  ray.t_max = 5.01;
  EXPECT_TRUE(square.occluded(ray));
}

TEST(Polygon, UvFollowTheFirstEdge) {
  // A square turned by 45°: the first edge runs along (1, 1)/√2, the frame's second axis along
  // (-1, 1)/√2, and the bounding rectangle in that frame is [0, √2]^2.
  const Polygon turned({{0, 0, 0}, {1, 1, 0}, {0, 2, 0}, {-1, 1, 0}});
  SurfaceHit hit;
  ASSERT_TRUE(turned.intersect(down_at(0, 1), hit));
  EXPECT_NEAR(hit.uv.x, 0.5, 1e-12);
  EXPECT_NEAR(hit.uv.y, 0.5, 1e-12);
  ASSERT_TRUE(turned.intersect(down_at(0.5, 0.5 + 1e-9), hit));
  EXPECT_NEAR(hit.uv.x, 0.5, 1e-8);
  EXPECT_NEAR(hit.uv.y, 0.0, 1e-8);
  EXPECT_NEAR(length(hit.dpdu - Vec3{1, 1, 0}), 0.0, 1e-12);   // √2 along (1, 1)/√2
  EXPECT_NEAR(length(hit.dpdv - Vec3{-1, 1, 0}), 0.0, 1e-12);  // √2 along (-1, 1)/√2
  // A triangle: the rectangle [0, 2] x [0, 1].
  const Polygon triangle({{0, 0, 0}, {2, 0, 0}, {0, 1, 0}});
  ASSERT_TRUE(triangle.intersect(down_at(0.5, 0.25), hit));
  EXPECT_NEAR(hit.uv.x, 0.25, 1e-12);
  EXPECT_NEAR(hit.uv.y, 0.25, 1e-12);
}

TEST(Polygon, Bounds) {
  const Bounds3 bounds = Polygon({{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}).bounds();
  EXPECT_EQ(bounds.lower, (Vec3{0, 0, 0}));
  EXPECT_EQ(bounds.upper, (Vec3{1, 1, 1}));
}

TEST(Polygon, RejectsBadArguments) {
  EXPECT_THROW(Polygon({{0, 0, 0}, {1, 0, 0}}), std::invalid_argument);
  EXPECT_THROW(Polygon({}), std::invalid_argument);
  EXPECT_THROW(Polygon({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}), std::invalid_argument);  // collinear
  EXPECT_THROW(Polygon({{0, 0, 0}, {0, 0, 0}, {0, 0, 0}}), std::invalid_argument);
  EXPECT_THROW(Polygon({{0, 0, 0}, {1, 0, 0}, {1, 1, 0.1}, {0, 1, 0}}),
               std::invalid_argument);  // not planar
  EXPECT_THROW(Polygon({{0, 0, 0}, {1, 0, 0}, {1, std::nan(""), 0}}), std::invalid_argument);
  // Self-intersecting (a bowtie, a pentagram through its five points) — no one fill rule
  // (the ray test's even-odd count against ear clipping's filled shape): refused, naming the edges.
  try {
    const Polygon bowtie({{0, 0, 0}, {2, 1, 0}, {2, 0, 0}, {0, 1.5, 0}});  // lobes of unequal area
    ADD_FAILURE() << "the bowtie was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("polygon edges 0–1 and 2–3 cross"), std::string::npos) << e.what();
  }
  std::vector<Vec3> pentagram;
  for (int i = 0; i < 5; ++i) {
    const double angle = (2 * i % 5) * 2 * kPi / 5;
    pentagram.push_back({std::cos(angle), std::sin(angle), 0});
  }
  try {
    const Polygon polygon(pentagram);
    ADD_FAILURE() << "the pentagram was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("polygon edges 0–1 and 2–3 cross"), std::string::npos) << e.what();
  }
  // Planar within the tolerance is accepted.
  EXPECT_NO_THROW(Polygon({{0, 0, 0}, {1, 0, 0}, {1, 1, 1e-9}, {0, 1, 0}}));
}

TEST(Polygon, TransformedLShape) {
  // The L scaled by 2, rotated 90° about +x (y -> z, z -> -y) and moved to the plane y = 3:
  // it covers x, z in [0,4]x[0,2] and [0,2]x[0,4]; the notch is x, z in (2, 4).
  const TransformedShape l(
      std::make_unique<Polygon>(l_shape()),
      Transform::translate({0, 3, 0}) * Transform::rotate(90, {1, 0, 0}) * Transform::scale({2, 2, 2}));
  SurfaceHit hit;
  ASSERT_TRUE(l.intersect(make_ray({1, 10, 3}, {0, -1, 0}), hit));
  EXPECT_NEAR(hit.t, 7.0, 1e-12);
  EXPECT_NEAR(hit.position.y, 3.0, 1e-12);
  EXPECT_NEAR(hit.geometric_normal.y, -1.0, 1e-12);  // +z turned to -y
  EXPECT_FALSE(l.intersect(make_ray({3, 10, 3}, {0, -1, 0}), hit));
  EXPECT_TRUE(l.intersect(make_ray({3, 10, 1}, {0, -1, 0}), hit));
  EXPECT_NEAR(l.bounds().upper.z, 4.0, 1e-12);
}

}  // namespace
}  // namespace candela
