#include "geometry/convex_triangulation.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

#include "math/constants.h"
#include "math/vector.h"

namespace candela {
namespace {

std::vector<Vec2> regular_polygon(uint32_t corners) {
  std::vector<Vec2> p;
  for (uint32_t i = 0; i < corners; ++i)
    p.push_back({std::cos(2 * kPi * i / corners), std::sin(2 * kPi * i / corners)});
  return p;
}

double twice_area(const Vec2& a, const Vec2& b, const Vec2& c) {
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

// A triangulation: corners − 2 counter-clockwise triangles whose directed edges are the polygon's
// edges once each and the diagonals once in each direction (so they tile the polygon without
// overlap or gap), and whose areas add up to the polygon's.
TEST(ConvexTriangulation, TilesTheRegularPolygonsOfEverySize) {
  for (const uint32_t corners :
       {3u, 4u, 5u, 6u, 7u, 8u, 9u, 10u, 11u, 12u, 13u, 31u, 64u, 100u, 1000u, 4097u}) {
    SCOPED_TRACE(corners);
    const std::vector<Vec2> p = regular_polygon(corners);
    const auto triangles = triangulate_convex_polygon(corners);
    ASSERT_EQ(triangles.size(), corners - 2u);
    std::map<std::pair<uint32_t, uint32_t>, int> edges;
    double area = 0;
    for (const auto& t : triangles) {
      for (const uint32_t i : t) ASSERT_LT(i, corners);
      const double twice = twice_area(p[t[0]], p[t[1]], p[t[2]]);
      ASSERT_GT(twice, 0) << t[0] << " " << t[1] << " " << t[2];
      area += twice / 2;
      for (int k = 0; k < 3; ++k) ++edges[{t[k], t[(k + 1) % 3]}];
    }
    EXPECT_NEAR(area, 0.5 * corners * std::sin(2 * kPi / corners), 1e-9);
    for (const auto& [edge, count] : edges) {
      EXPECT_EQ(count, 1) << edge.first << "→" << edge.second;
      const bool boundary = edge.second == (edge.first + 1) % corners;
      EXPECT_EQ(edges.count({edge.second, edge.first}), boundary ? 0u : 1u)
          << edge.first << "→" << edge.second;
    }
    for (uint32_t i = 0; i < corners; ++i) EXPECT_EQ(edges.count({i, (i + 1) % corners}), 1u) << i;
  }
  EXPECT_TRUE(triangulate_convex_polygon(2).empty());
}

// What the halving is for: of the 99,998 triangles of a 10⁵-corner disc, few have a box that holds
// a given point (a fan from corner 0: tens of thousands — every box reaches corner 0).
TEST(ConvexTriangulation, FewTrianglesOfAHugeDiscHaveABoxOverAnyPoint) {
  constexpr uint32_t kCorners = 100000;
  const std::vector<Vec2> p = regular_polygon(kCorners);
  struct Box {
    double x0, x1, y0, y1;
  };
  std::vector<Box> boxes;
  for (const auto& t : triangulate_convex_polygon(kCorners)) {
    const auto [x0, x1] = std::minmax({p[t[0]].x, p[t[1]].x, p[t[2]].x});
    const auto [y0, y1] = std::minmax({p[t[0]].y, p[t[1]].y, p[t[2]].y});
    boxes.push_back({x0, x1, y0, y1});
  }
  std::size_t most = 0;
  for (double x = -0.95; x < 1; x += 0.1)
    for (double y = -0.95; y < 1; y += 0.1) {
      if (x * x + y * y > 1) continue;
      const auto holding = std::count_if(boxes.begin(), boxes.end(), [&](const Box& b) {
        return b.x0 <= x && x <= b.x1 && b.y0 <= y && y <= b.y1;
      });
      most = std::max(most, static_cast<std::size_t>(holding));
    }
  EXPECT_LE(most, 40u);  // log₂ 10⁵ ≈ 17 levels, a few boxes each
  EXPECT_GE(most, 1u);
}

}  // namespace
}  // namespace candela
