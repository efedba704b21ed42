#include "raster/rasterizer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>
#include <vector>

#include "camera/perspective_camera.h"
#include "geometry/triangle_mesh.h"
#include "math/constants.h"
#include "math/pcg32.h"

namespace candela {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// A vertex placed at screen position (x, y) of a width × height image, ndc depth z, with clip
// w = w (x, y, z scaled by w: the same screen position for any w > 0). For power-of-two sizes
// and coordinates on a fine lattice the round trip to the screen is exact.
RasterVertex screen_vertex(double x, double y, int width, int height, double z = 0, double w = 1) {
  RasterVertex v;
  const double ndc_x = 2 * x / width - 1, ndc_y = 1 - 2 * y / height;
  v.clip = Eigen::Vector4d(ndc_x * w, ndc_y * w, z * w, w);
  v.varyings.fill(0);
  return v;
}

struct Point {
  double x, y;
};

// Twice the signed area of (a, b, p): > 0 when p lies to one side of a → b.
double edge_function(const Point& a, const Point& b, const Point& p) {
  return (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x);
}

// An independent statement of the top-left rule, with edge functions instead of scanlines: a
// centre strictly inside is covered; one on an edge only when the triangle's interior lies to
// the edge's right (+x: a left edge) or, for a horizontal edge, below it (+y: a top edge).
bool top_left_covers(const Point& p0, const Point& p1, const Point& p2, const Point& p) {
  const double area = edge_function(p0, p1, p2);
  if (area == 0) return false;
  const double sign = area > 0 ? 1 : -1;
  const Point corners[3] = {p0, p1, p2};
  for (int i = 0; i < 3; ++i) {
    const Point& a = corners[i];
    const Point& b = corners[(i + 1) % 3];
    const double e = sign * edge_function(a, b, p);
    if (e < 0) return false;
    if (e == 0) {
      // The inward normal of the edge (the gradient of the signed edge function).
      const double normal_x = -sign * (b.y - a.y), normal_y = sign * (b.x - a.x);
      if (!(normal_x > 0 || (normal_x == 0 && normal_y > 0))) return false;
    }
  }
  return true;
}

// Counts the fragments of every pixel; returns false so that the depth buffer stays at +∞ and
// every later triangle is tested afresh (the depth test "disabled").
class CoverageCounter {
 public:
  CoverageCounter(int width, int height)
      : width_(width), counts_(static_cast<std::size_t>(width * height), 0) {}
  auto callback() {
    return [this](const Fragment& f) {
      ++counts_[static_cast<std::size_t>(f.y * width_ + f.x)];
      return false;
    };
  }
  int at(int x, int y) const { return counts_[static_cast<std::size_t>(y * width_ + x)]; }

 private:
  int width_;
  std::vector<int> counts_;
};

void draw_screen_triangle(Rasterizer& rasterizer, const Point& a, const Point& b, const Point& c,
                          CoverageCounter& counter, double wa = 1, double wb = 1, double wc = 1) {
  const int width = rasterizer.width(), height = rasterizer.height();
  rasterizer.draw_triangle(screen_vertex(a.x, a.y, width, height, 0, wa),
                           screen_vertex(b.x, b.y, width, height, 0, wb),
                           screen_vertex(c.x, c.y, width, height, 0, wc), 0, counter.callback());
}

TEST(Raster, RightTrianglesOnPixelCentresFollowTheTopLeftRule) {
  // Two halves of the square of centres [2.5, 10.5]²: every edge runs through pixel centres.
  const int size = 16;
  for (const bool reversed : {false, true}) {
    Rasterizer rasterizer(size, size);
    CoverageCounter upper(size, size), lower(size, size);
    // Upper-left half: top edge y = 2.5 (in), left edge x = 2.5 (in), hypotenuse (its right: out).
    const Point a{2.5, 2.5}, b{10.5, 2.5}, c{2.5, 10.5}, d{10.5, 10.5};
    if (reversed) {
      draw_screen_triangle(rasterizer, c, b, a, upper);
      draw_screen_triangle(rasterizer, c, d, b, lower);
    } else {
      draw_screen_triangle(rasterizer, a, b, c, upper);
      draw_screen_triangle(rasterizer, b, d, c, lower);
    }
    for (int y = 0; y < size; ++y) {
      for (int x = 0; x < size; ++x) {
        const double xc = x + 0.5, yc = y + 0.5;
        const bool in_upper = xc >= 2.5 && yc >= 2.5 && xc + yc < 13;
        // Lower-right half: hypotenuse (its left: in), right edge x = 10.5 and bottom y = 10.5 out.
        const bool in_lower = xc + yc >= 13 && xc < 10.5 && yc < 10.5;
        EXPECT_EQ(upper.at(x, y), in_upper ? 1 : 0) << x << "," << y << " reversed " << reversed;
        EXPECT_EQ(lower.at(x, y), in_lower ? 1 : 0) << x << "," << y << " reversed " << reversed;
      }
    }
  }
}

TEST(Raster, CentresOnEveryKindOfEdgeFollowTheTopLeftRule) {
  // Corners on a quarter-pixel lattice, chosen so that edges of every slope run through pixel
  // centres (all the arithmetic is exact there), plus the hand-made cases: a flat top, a flat
  // bottom, a vertical left and right edge, apexes on centres. Both windings, and w ≠ 1.
  const int size = 32;
  std::vector<std::array<Point, 3>> triangles = {
      {Point{4.5, 4.5}, Point{20.5, 4.5}, Point{12.5, 20.5}},    // flat top through centres
      {Point{12.5, 3.5}, Point{4.5, 19.5}, Point{20.5, 19.5}},   // flat bottom through centres
      {Point{5.5, 2.5}, Point{5.5, 22.5}, Point{17.5, 12.5}},    // vertical left edge on centres
      {Point{25.5, 2.5}, Point{25.5, 22.5}, Point{13.5, 12.5}},  // vertical right edge on centres
      {Point{3.5, 3.5}, Point{27.5, 9.5}, Point{9.5, 27.5}},     // slopes 1/4 and 4 through centres
      {Point{16.5, 1.5}, Point{30.5, 15.5}, Point{2.5, 29.5}},   // slopes ±1 (diagonals of centres)
      {Point{8, 8}, Point{24, 8}, Point{8, 24}},                 // corners on pixel corners
  };
  Pcg32 random(7, 1);
  for (int i = 0; i < 300; ++i) {
    std::array<Point, 3> t;
    for (Point& p : t)
      p = {std::floor(random.next_double() * 4 * size) / 4, std::floor(random.next_double() * 4 * size) / 4};
    triangles.push_back(t);
  }
  // Corners on pixel centres: their edges run through further centres whenever the steps in x
  // and y share a factor, at every slope (3/6, 9/6, 10/15, ...).
  for (int i = 0; i < 300; ++i) {
    std::array<Point, 3> t;
    for (Point& p : t)
      p = {std::floor(random.next_double() * size) + 0.5, std::floor(random.next_double() * size) + 0.5};
    triangles.push_back(t);
  }
  for (const auto& t : triangles) {
    for (const bool reversed : {false, true}) {
      Rasterizer rasterizer(size, size);
      CoverageCounter counter(size, size);
      if (reversed)
        draw_screen_triangle(rasterizer, t[2], t[1], t[0], counter, 4, 0.5, 2);
      else
        draw_screen_triangle(rasterizer, t[0], t[1], t[2], counter, 2, 1, 0.25);
      for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x)
          ASSERT_EQ(counter.at(x, y), top_left_covers(t[0], t[1], t[2], {x + 0.5, y + 0.5}) ? 1 : 0)
              << "pixel " << x << "," << y << " triangle (" << t[0].x << "," << t[0].y << ") (" << t[1].x
              << "," << t[1].y << ") (" << t[2].x << "," << t[2].y << ") reversed " << reversed;
    }
  }
}

// A star-shaped fan around centre: rim[i], rim[i+1] and the centre. Every pixel centre strictly
// inside the union is covered exactly once, none outside; one on the outer boundary at most once.
void expect_fan_covers_once(const Point& centre, const std::vector<Point>& rim, Pcg32& random, bool random_w,
                            int size) {
  Rasterizer rasterizer(size, size);
  CoverageCounter counter(size, size);
  const auto w_of = [&] { return random_w ? 0.25 + 4 * random.next_double() : 1.0; };
  const double centre_w = w_of();
  std::vector<double> rim_w(rim.size());
  for (double& w : rim_w) w = w_of();
  for (std::size_t i = 0; i < rim.size(); ++i) {
    const std::size_t j = (i + 1) % rim.size();
    // Alternate the windings: the core draws both.
    if (i % 2 == 0)
      draw_screen_triangle(rasterizer, centre, rim[i], rim[j], counter, centre_w, rim_w[i], rim_w[j]);
    else
      draw_screen_triangle(rasterizer, rim[j], rim[i], centre, counter, rim_w[j], rim_w[i], centre_w);
  }
  int covered = 0;
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      const Point p{x + 0.5, y + 0.5};
      bool strictly_inside = false, on_outer_edge = false;
      for (std::size_t i = 0; i < rim.size(); ++i) {
        const Point& a = rim[i];
        const Point& b = rim[(i + 1) % rim.size()];
        const double area = edge_function(centre, a, b);
        const double s = area > 0 ? 1 : -1;
        const double e0 = s * edge_function(centre, a, p), e1 = s * edge_function(a, b, p),
                     e2 = s * edge_function(b, centre, p);
        if (e0 >= 0 && e1 >= 0 && e2 >= 0) {
          if (e1 == 0)
            on_outer_edge = true;
          else
            strictly_inside = true;  // inside, on a spoke or at the centre: interior of the union
        }
      }
      const int count = counter.at(x, y);
      covered += count;
      if (strictly_inside && !on_outer_edge)
        ASSERT_EQ(count, 1) << "pixel " << x << "," << y;
      else if (on_outer_edge)
        ASSERT_LE(count, 1) << "pixel " << x << "," << y;
      else
        ASSERT_EQ(count, 0) << "pixel " << x << "," << y;
    }
  }
  EXPECT_GT(covered, 0);
}

TEST(Raster, FanAroundACentreCoversEveryPixelOnce) {
  const int size = 64;
  Pcg32 random(11, 3);
  // On the lattice: the centre on a pixel centre, spokes horizontal, vertical, diagonal and of
  // slopes 1/2 and 2, all through pixel centres; the rim on centres and on pixel corners.
  const Point centre{32.5, 32.5};
  const std::vector<Point> lattice_rim = {{52.5, 32.5}, {50.5, 41.5}, {46.5, 46.5}, {41.5, 50.5},
                                          {32.5, 52.5}, {23, 50},     {18.5, 46.5}, {14.5, 41.5},
                                          {12.5, 32.5}, {14.5, 23.5}, {18.5, 18.5}, {24, 15},
                                          {32.5, 12.5}, {42.5, 14.5}, {46.5, 18.5}, {50.5, 22.5}};
  expect_fan_covers_once(centre, lattice_rim, random, false, size);
  expect_fan_covers_once(centre, lattice_rim, random, true, size);
  // Random non-integer positions: 3 to 40 spokes around a random centre, random w (perspective).
  for (int fan = 0; fan < 60; ++fan) {
    const Point c{24 + 16 * random.next_double(), 24 + 16 * random.next_double()};
    const int spokes = 3 + static_cast<int>(random.next_uint() % 38);
    std::vector<Point> rim;
    for (int i = 0; i < spokes; ++i) {
      const double angle = 2 * kPi * (i + 0.8 * random.next_double()) / spokes;
      const double radius = 6 + 18 * random.next_double();
      rim.push_back({c.x + radius * std::cos(angle), c.y + radius * std::sin(angle)});
    }
    expect_fan_covers_once(c, rim, random, fan % 2 == 1, size);
  }
}

// A grid of quads over [x_min, x_max] × [y_min, y_max] with jittered inner vertices, each quad
// split along a random diagonal and drawn in a random winding: every centre of the rectangle is
// covered exactly once (the rectangle's own sides by the top-left rule), none outside.
void expect_grid_covers_once(const std::vector<double>& xs, const std::vector<double>& ys,
                             const std::function<Point(int, int)>& vertex, Pcg32& random, bool random_w,
                             int size) {
  const int columns = static_cast<int>(xs.size()), rows = static_cast<int>(ys.size());
  std::vector<Point> points;
  std::vector<double> ws;
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < columns; ++i) {
      points.push_back(vertex(i, j));
      ws.push_back(random_w ? 0.25 + 4 * random.next_double() : 1.0);
    }
  Rasterizer rasterizer(size, size);
  CoverageCounter counter(size, size);
  const auto index = [&](int i, int j) { return static_cast<std::size_t>(j * columns + i); };
  const auto draw = [&](std::size_t a, std::size_t b, std::size_t c) {
    if (random.next_uint() % 2)
      draw_screen_triangle(rasterizer, points[a], points[b], points[c], counter, ws[a], ws[b], ws[c]);
    else
      draw_screen_triangle(rasterizer, points[c], points[b], points[a], counter, ws[c], ws[b], ws[a]);
  };
  for (int j = 0; j + 1 < rows; ++j)
    for (int i = 0; i + 1 < columns; ++i) {
      const std::size_t a = index(i, j), b = index(i + 1, j), c = index(i + 1, j + 1), d = index(i, j + 1);
      if (random.next_uint() % 2) {
        draw(a, b, c);
        draw(a, c, d);
      } else {
        draw(a, b, d);
        draw(b, c, d);
      }
    }
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const double xc = x + 0.5, yc = y + 0.5;
      const bool inside = xc >= xs.front() && xc < xs.back() && yc >= ys.front() && yc < ys.back();
      ASSERT_EQ(counter.at(x, y), inside ? 1 : 0) << "pixel " << x << "," << y;
    }
}

TEST(Raster, GridOfQuadsCoversEveryPixelOnce) {
  const int size = 64;
  Pcg32 random(5, 9);
  for (int trial = 0; trial < 20; ++trial) {
    // Random non-integer positions: grid lines anywhere, inner vertices jittered by up to 10%
    // of the narrower neighbouring cell (the quads stay convex); random w.
    std::vector<double> xs{3.3}, ys{5.7};
    while (xs.back() < 55) xs.push_back(xs.back() + 0.7 + 5 * random.next_double());
    while (ys.back() < 55) ys.push_back(ys.back() + 0.7 + 5 * random.next_double());
    const auto jittered = [&](int i, int j) {
      Point p{xs[static_cast<std::size_t>(i)], ys[static_cast<std::size_t>(j)]};
      const bool inner_x = i > 0 && i + 1 < static_cast<int>(xs.size());
      const bool inner_y = j > 0 && j + 1 < static_cast<int>(ys.size());
      if (inner_x)
        p.x += 0.2 * (random.next_double() - 0.5) *
               std::min(xs[static_cast<std::size_t>(i)] - xs[static_cast<std::size_t>(i - 1)],
                        xs[static_cast<std::size_t>(i + 1)] - xs[static_cast<std::size_t>(i)]);
      if (inner_y)
        p.y += 0.2 * (random.next_double() - 0.5) *
               std::min(ys[static_cast<std::size_t>(j)] - ys[static_cast<std::size_t>(j - 1)],
                        ys[static_cast<std::size_t>(j + 1)] - ys[static_cast<std::size_t>(j)]);
      return p;
    };
    expect_grid_covers_once(xs, ys, jittered, random, trial % 2 == 1, size);

    // On the lattice: grid lines on pixel centres and pixel corners, inner vertices moved by
    // whole or half pixels (so every edge and corner can fall exactly on centres), w powers of 2.
    std::vector<double> lx{2.5}, ly{4};
    while (lx.back() < 52) lx.push_back(lx.back() + 3 + 0.5 * (random.next_uint() % 9));
    while (ly.back() < 52) ly.push_back(ly.back() + 3 + 0.5 * (random.next_uint() % 9));
    const auto on_lattice = [&](int i, int j) {
      Point p{lx[static_cast<std::size_t>(i)], ly[static_cast<std::size_t>(j)]};
      if (i > 0 && i + 1 < static_cast<int>(lx.size()))
        p.x += 0.5 * (static_cast<int>(random.next_uint() % 3) - 1);
      if (j > 0 && j + 1 < static_cast<int>(ly.size()))
        p.y += 0.5 * (static_cast<int>(random.next_uint() % 3) - 1);
      return p;
    };
    expect_grid_covers_once(lx, ly, on_lattice, random, false, size);
  }
}

TEST(Raster, AffineVaryingIsTheLinearFunctionAtPixelCentres) {
  // With w = 1 everywhere the varyings are linear in screen space: a varying equal to screen x
  // (and one equal to 3y − x) is exactly that at every centre, to rounding; depth likewise.
  const int width = 64, height = 32;
  Rasterizer rasterizer(width, height);
  const Point corners[3] = {{3.2, 1.7}, {60.1, 12.3}, {20.4, 30.9}};
  RasterVertex v[3];
  for (int i = 0; i < 3; ++i) {
    v[i] = screen_vertex(corners[i].x, corners[i].y, width, height,
                         0.1 * corners[i].x / width - 0.02 * corners[i].y / height);
    v[i].varyings[0] = corners[i].x;
    v[i].varyings[1] = 3 * corners[i].y - corners[i].x;
  }
  int count = 0;
  rasterizer.draw_triangle(v[0], v[1], v[2], 2, [&](const Fragment& f) {
    const double xc = f.x + 0.5, yc = f.y + 0.5;
    EXPECT_NEAR(f.varyings[0], xc, 1e-12);
    EXPECT_NEAR(f.varyings[1], 3 * yc - xc, 1e-12);
    EXPECT_NEAR(f.depth, 0.1 * xc / width - 0.02 * yc / height, 1e-14);
    ++count;
    return true;
  });
  EXPECT_GT(count, 500);
  EXPECT_EQ(static_cast<uint64_t>(count), rasterizer.statistics().written);
}

TEST(Raster, DepthTestKeepsTheNearerTriangleInEitherOrder) {
  const int size = 32;
  // Two crossing triangles: A's depth falls from left to right, B is flat in between, so each
  // is in front over part of the overlap.
  RasterVertex a[3] = {screen_vertex(2, 2, size, size, 0.8), screen_vertex(30, 4, size, size, -0.8),
                       screen_vertex(10, 30, size, size, 0.8)};
  RasterVertex b[3] = {screen_vertex(4, 6, size, size, 0.0), screen_vertex(28, 10, size, size, 0.0),
                       screen_vertex(20, 28, size, size, 0.0)};
  std::vector<int> first(size * size, -1), second(size * size, -1);
  for (const bool a_first : {true, false}) {
    Rasterizer rasterizer(size, size);
    std::vector<int>& ids = a_first ? first : second;
    const auto draw = [&](RasterVertex* v, int id) {
      rasterizer.draw_triangle(v[0], v[1], v[2], 0, [&](const Fragment& f) {
        ids[static_cast<std::size_t>(f.y * size + f.x)] = id;
        return true;
      });
    };
    if (a_first) {
      draw(a, 0);
      draw(b, 1);
    } else {
      draw(b, 1);
      draw(a, 0);
    }
  }
  EXPECT_EQ(first, second);
  int a_seen = 0, b_seen = 0;
  for (const int id : first) {
    a_seen += id == 0;
    b_seen += id == 1;
  }
  EXPECT_GT(a_seen, 20);
  EXPECT_GT(b_seen, 20);

  // Strictly less: a second triangle at exactly the same depth does not replace the first.
  Rasterizer rasterizer(size, size);
  int replaced = 0;
  rasterizer.draw_triangle(b[0], b[1], b[2], 0, [](const Fragment&) { return true; });
  rasterizer.draw_triangle(b[0], b[1], b[2], 0, [&](const Fragment&) { return ++replaced, true; });
  EXPECT_EQ(replaced, 0);
  EXPECT_EQ(rasterizer.depth_at(16, 12), 0.0);
  EXPECT_EQ(rasterizer.depth_at(0, 31), kInfinity);
}

TEST(Raster, RegionGivenAtConstructionDrawsAsSetRegionDoes) {
  const int size = 64;
  const RasterVertex v[3] = {screen_vertex(3, 5, size, size, 0.1), screen_vertex(60, 9, size, size, 0.2),
                             screen_vertex(20, 61, size, size, 0.3)};
  Rasterizer tiled(size, size, 16, 8, 48, 40);
  Rasterizer whole(size, size);
  whole.set_region(16, 8, 48, 40);
  std::vector<std::pair<int, int>> from_tiled, from_whole;
  tiled.draw_triangle(v[0], v[1], v[2], 0,
                      [&](const Fragment& f) { return from_tiled.emplace_back(f.x, f.y), true; });
  whole.draw_triangle(v[0], v[1], v[2], 0,
                      [&](const Fragment& f) { return from_whole.emplace_back(f.x, f.y), true; });
  EXPECT_EQ(from_tiled, from_whole);
  EXPECT_GT(from_tiled.size(), 100u);
  for (const auto& [x, y] : from_tiled) {
    EXPECT_TRUE(x >= 16 && x < 48 && y >= 8 && y < 40);
    EXPECT_EQ(tiled.depth_at(x, y), whole.depth_at(x, y));
  }
  EXPECT_THROW(Rasterizer(size, size, 0, 0, size + 1, size), std::invalid_argument);
}

TEST(Raster, ShadeReturningFalseLeavesTheDepthBuffer) {
  const int size = 16;
  Rasterizer rasterizer(size, size);
  RasterVertex near_triangle[3] = {screen_vertex(0, 0, size, size, -0.5),
                                   screen_vertex(16, 0, size, size, -0.5),
                                   screen_vertex(0, 16, size, size, -0.5)};
  RasterVertex far_triangle[3] = {screen_vertex(0, 0, size, size, 0.5), screen_vertex(16, 0, size, size, 0.5),
                                  screen_vertex(0, 16, size, size, 0.5)};
  rasterizer.draw_triangle(near_triangle[0], near_triangle[1], near_triangle[2], 0,
                           [](const Fragment&) { return false; });  // see-through
  EXPECT_EQ(rasterizer.depth_at(2, 2), kInfinity);
  int drawn = 0;
  rasterizer.draw_triangle(far_triangle[0], far_triangle[1], far_triangle[2], 0,
                           [&](const Fragment&) { return ++drawn, true; });
  EXPECT_EQ(drawn, 120);  // 15·16/2: the centres with x_c + y_c < 16 (the diagonal is a right edge)
  EXPECT_EQ(rasterizer.depth_at(2, 2), 0.5);
  EXPECT_EQ(rasterizer.statistics().fragments, 240u);
  EXPECT_EQ(rasterizer.statistics().written, 120u);
}

// A camera and the world-space triangles of the perspective and clipping tests.
struct ViewSetup {
  PerspectiveCamera camera{{0.3, 0.2, 4}, {0, 0, 0}, {0, 1, 0}, 60, 80, 60};
  double near = 0.5, far = 20;
  Eigen::Matrix4d clip_from_world = camera.view_projection(near, far);

  RasterVertex vertex(const Vec3& p) const {
    RasterVertex v;
    v.clip = clip_from_world * Eigen::Vector4d(p.x, p.y, p.z, 1);
    v.varyings.fill(0);
    v.varyings[0] = p.x;
    v.varyings[1] = p.y;
    v.varyings[2] = p.z;
    return v;
  }
  // The ray of a pixel centre, limited to the view depths near … far (the clipped volume).
  Ray pixel_ray(int x, int y) const {
    Ray ray = camera.generate_ray(x + 0.5, y + 0.5);
    const double cosine = dot(ray.direction, camera.gaze());
    ray.t_min = near / cosine;
    ray.t_max = far / cosine;
    return ray;
  }
  double ndc_depth(const Vec3& p) const {
    const Eigen::Vector4d clip = clip_from_world * Eigen::Vector4d(p.x, p.y, p.z, 1);
    return clip.z() / clip.w();
  }
};

// Draws the triangle and compares every pixel with a ray caster: the same pixels, and the
// varyings (the world position) and depth at the ray's hit. Returns the pixels drawn.
int expect_matches_ray_caster(const ViewSetup& scene, const Vec3& p0, const Vec3& p1, const Vec3& p2,
                              double tolerance) {
  const int width = scene.camera.width(), height = scene.camera.height();
  Rasterizer rasterizer(width, height);
  std::vector<int> drawn(static_cast<std::size_t>(width * height), 0);
  rasterizer.draw_triangle(scene.vertex(p0), scene.vertex(p1), scene.vertex(p2), 3, [&](const Fragment& f) {
    ++drawn[static_cast<std::size_t>(f.y * width + f.x)];
    TriangleIntersection hit;
    const Ray ray = scene.pixel_ray(f.x, f.y);
    if (!intersect_triangle(ray, p0, p1, p2, hit)) {
      ADD_FAILURE() << "drawn but the ray misses: " << f.x << "," << f.y;
      return true;
    }
    const Vec3 world = ray.at(hit.t);
    EXPECT_NEAR(f.varyings[0], world.x, tolerance) << f.x << "," << f.y;
    EXPECT_NEAR(f.varyings[1], world.y, tolerance) << f.x << "," << f.y;
    EXPECT_NEAR(f.varyings[2], world.z, tolerance) << f.x << "," << f.y;
    EXPECT_NEAR(f.depth, scene.ndc_depth(world), tolerance) << f.x << "," << f.y;
    return true;
  });
  int count = 0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      TriangleIntersection hit;
      const bool seen = intersect_triangle(scene.pixel_ray(x, y), p0, p1, p2, hit);
      EXPECT_EQ(drawn[static_cast<std::size_t>(y * width + x)], seen ? 1 : 0) << "pixel " << x << "," << y;
      count += seen;
    }
  return count;
}

TEST(Raster, PerspectiveCorrectVaryingsEqualTheRayHit) {
  // A slanted quad (two triangles sharing a diagonal) filling much of the view: the varying
  // equal to the world position is the world position of the ray's hit, to 1e-9.
  const ViewSetup scene;
  const Vec3 a{-2.1, -1.3, -1.7}, b{1.9, -1.6, 0.9}, c{2.3, 1.4, -0.4}, d{-1.7, 1.8, -3.1};
  const int first = expect_matches_ray_caster(scene, a, b, c, 1e-9);
  const int second = expect_matches_ray_caster(scene, a, c, d, 1e-9);
  EXPECT_GT(first + second, 1500);
}

TEST(Raster, NearAndFarClippingMatchARayCaster) {
  const ViewSetup scene;  // eye (0.3, 0.2, 4) looking toward the origin; near 0.5, far 20
  // Crossing the eye plane: one corner behind the eye, the others in front.
  EXPECT_GT(expect_matches_ray_caster(scene, {0.1, -0.9, 6.5}, {-1.3, -0.7, 1.2}, {1.7, 0.4, 0.9}, 1e-9),
            100);
  // Two corners behind the eye (a quad after clipping).
  EXPECT_GT(expect_matches_ray_caster(scene, {-2.2, -1.1, 7.3}, {2.9, -0.8, 5.9}, {0.4, 1.3, -1.1}, 1e-9),
            100);
  // A corner in the eye plane beside the eye (w = 0 there).
  const Vec3 beside_eye = scene.camera.eye_position() + normalize(scene.camera.half_width()) * 1.5;
  EXPECT_GT(expect_matches_ray_caster(scene, beside_eye, {-1.4, -1.1, 0.3}, {1.2, -0.2, -0.8}, 1e-9), 50);
  // Crossing the far plane (cut there) and both planes at once.
  EXPECT_GT(expect_matches_ray_caster(scene, {-1.2, -0.9, 1.1}, {3.1, 0.8, -30}, {-4.4, 2.2, -25}, 1e-9),
            100);
  EXPECT_GT(expect_matches_ray_caster(scene, {0.2, -1.1, 9}, {6.3, 0.8, -40}, {-7.4, 3.1, -35}, 1e-9), 100);
}

TEST(Raster, MeshCutByTheNearAndFarPlanesStaysWatertight) {
  // A floor of jittered quads reaching behind the eye and beyond the far plane: the triangles
  // cut by a depth plane share their clipped vertices bit for bit, so every pixel whose ray
  // meets the floor between near and far is covered exactly once, and no other.
  const ViewSetup scene;
  const int width = scene.camera.width(), height = scene.camera.height();
  Pcg32 random(21, 8);
  const int cells = 14;
  const double x0 = -6, x1 = 6, z0 = -30, z1 = 9, floor_y = -0.8;
  std::vector<Vec3> points;
  for (int j = 0; j <= cells; ++j)
    for (int i = 0; i <= cells; ++i) {
      double x = x0 + (x1 - x0) * i / cells, z = z0 + (z1 - z0) * j / cells;
      if (i > 0 && i < cells) x += 0.3 * (random.next_double() - 0.5) * (x1 - x0) / cells;
      if (j > 0 && j < cells) z += 0.3 * (random.next_double() - 0.5) * (z1 - z0) / cells;
      points.push_back({x, floor_y, z});
    }
  Rasterizer rasterizer(width, height);
  std::vector<int> counts(static_cast<std::size_t>(width * height), 0);
  const auto count = [&](const Fragment& f) {
    ++counts[static_cast<std::size_t>(f.y * width + f.x)];
    return false;
  };
  const auto at = [&](int i, int j) {
    return scene.vertex(points[static_cast<std::size_t>(j * (cells + 1) + i)]);
  };
  for (int j = 0; j < cells; ++j)
    for (int i = 0; i < cells; ++i) {
      if ((i + j) % 2) {
        rasterizer.draw_triangle(at(i, j), at(i + 1, j), at(i + 1, j + 1), 3, count);
        rasterizer.draw_triangle(at(i + 1, j + 1), at(i, j + 1), at(i, j), 3, count);
      } else {
        rasterizer.draw_triangle(at(i, j), at(i + 1, j), at(i, j + 1), 3, count);
        rasterizer.draw_triangle(at(i + 1, j), at(i + 1, j + 1), at(i, j + 1), 3, count);
      }
    }
  EXPECT_GT(rasterizer.statistics().clipped, 10u);
  int covered = 0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const Ray ray = scene.pixel_ray(x, y);
      const double t = (floor_y - ray.origin.y) / ray.direction.y;
      const Vec3 hit = ray.at(t);
      const bool seen =
          t > ray.t_min && t < ray.t_max && hit.x > x0 && hit.x < x1 && hit.z > z0 && hit.z < z1;
      ASSERT_EQ(counts[static_cast<std::size_t>(y * width + x)], seen ? 1 : 0) << "pixel " << x << "," << y;
      covered += seen;
    }
  EXPECT_GT(covered, width * height / 4);
}

TEST(Raster, SkipsTrianglesThatCannotBeDrawn) {
  const ViewSetup scene;
  const int width = scene.camera.width(), height = scene.camera.height();
  Rasterizer rasterizer(width, height);
  int fragments = 0;
  const auto count = [&](const Fragment&) { return ++fragments, true; };
  // Entirely behind the eye.
  rasterizer.draw_triangle(scene.vertex({0, 0, 6}), scene.vertex({1, 0, 7}), scene.vertex({0, 1, 8}), 3,
                           count);
  // Every corner at the eye (w = 0 and outside the near plane).
  const RasterVertex at_eye = scene.vertex(scene.camera.eye_position());
  rasterizer.draw_triangle(at_eye, at_eye, at_eye, 3, count);
  // Not a number, and infinite.
  RasterVertex not_a_number = scene.vertex({0, 0, 0});
  not_a_number.clip.x() = kNaN;
  rasterizer.draw_triangle(not_a_number, scene.vertex({1, 0, 0}), scene.vertex({0, 1, 0}), 3, count);
  RasterVertex infinite = scene.vertex({0, 0, 0});
  infinite.clip.w() = kInfinity;
  rasterizer.draw_triangle(scene.vertex({1, 0, 0}), infinite, scene.vertex({0, 1, 0}), 3, count);
  // w = 0 exactly with z = 0: on both depth planes at once, no screen position.
  RasterVertex nowhere = scene.vertex({0, 0, 0});
  nowhere.clip = Eigen::Vector4d(0.5, 0.25, 0, 0);
  rasterizer.draw_triangle(nowhere, scene.vertex({1, 0, 0}), scene.vertex({0, 1, 0}), 3, count);
  EXPECT_EQ(fragments, 0);
  EXPECT_EQ(rasterizer.statistics().triangles, 5u);
  EXPECT_EQ(rasterizer.statistics().culled, 5u);

  // Zero area on screen: collinear corners (exactly, on the lattice).
  Rasterizer square(64, 64);
  square.draw_triangle(screen_vertex(1, 1, 64, 64), screen_vertex(5, 5, 64, 64), screen_vertex(9, 9, 64, 64),
                       0, count);
  square.draw_triangle(screen_vertex(1, 3, 64, 64), screen_vertex(1, 3, 64, 64, 0, 2),
                       screen_vertex(1, 3, 64, 64), 0, count);
  EXPECT_EQ(fragments, 0);
  EXPECT_EQ(square.statistics().culled, 2u);

  // w ≈ 0: corners with tiny w (points near infinity) and corners with tiny w far off to the side
  // (huge screen coordinates): whatever is drawn has finite depth and varyings, inside the image.
  Pcg32 random(1, 2);
  for (int i = 0; i < 200; ++i) {
    RasterVertex corners[3];
    for (RasterVertex& v : corners) {
      const double w = std::pow(10.0, -300 * random.next_double());
      v.clip = Eigen::Vector4d(2 * random.next_double() - 1, 2 * random.next_double() - 1,
                               2 * random.next_double() - 1, 1) *
               w;
      if (random.next_uint() % 3 == 0) v.clip.w() *= 1e-6;  // far outside the side planes
      v.varyings.fill(random.next_double());
    }
    rasterizer.draw_triangle(corners[0], corners[1], corners[2], 2, [&](const Fragment& f) {
      EXPECT_TRUE(f.x >= 0 && f.x < width && f.y >= 0 && f.y < height);
      EXPECT_TRUE(std::isfinite(f.depth) && std::isfinite(f.varyings[0]) && std::isfinite(f.varyings[1]));
      return true;
    });
  }
}

TEST(Raster, StatisticsCountTrianglesCulledClippedAndFragments) {
  const int size = 16;
  Rasterizer rasterizer(size, size);
  int offered = 0;
  const auto count = [&](const Fragment&) { return ++offered, false; };  // depth buffer untouched
  // Inside: the 120 centres with x_c + y_c < 16.
  rasterizer.draw_triangle(screen_vertex(0, 0, size, size), screen_vertex(16, 0, size, size),
                           screen_vertex(0, 16, size, size), 0, count);
  EXPECT_EQ(offered, 120);
  // Outside the left plane (x < −w everywhere): culled.
  rasterizer.draw_triangle(screen_vertex(-10, 0, size, size), screen_vertex(-1, 5, size, size),
                           screen_vertex(-3, 9, size, size), 0, count);
  // Crossing the far plane (one corner at ndc z = 3): clipped, drawn in part.
  rasterizer.draw_triangle(screen_vertex(0.3, 0.1, size, size, 0.2), screen_vertex(15.9, 0.2, size, size, 3),
                           screen_vertex(0.1, 15.7, size, size, 0.2), 0, count);
  // Zero area.
  rasterizer.draw_triangle(screen_vertex(1, 1, size, size), screen_vertex(5, 5, size, size),
                           screen_vertex(9, 9, size, size), 0, count);
  const RasterStatistics& s = rasterizer.statistics();
  EXPECT_EQ(s.triangles, 4u);
  EXPECT_EQ(s.culled, 2u);
  EXPECT_EQ(s.clipped, 1u);
  EXPECT_EQ(s.fragments, static_cast<uint64_t>(offered));  // the buffer stayed at +∞: all offered
  EXPECT_GT(offered, 120 + 30);
  EXPECT_EQ(s.written, 0u);

  // Written: the fragments the callback accepted (every other one here).
  int accepted = 0, calls = 0;
  rasterizer.draw_triangle(screen_vertex(0, 0, size, size), screen_vertex(16, 0, size, size),
                           screen_vertex(0, 16, size, size), 0,
                           [&](const Fragment&) { return (calls++ % 2 == 0) ? (++accepted, true) : false; });
  EXPECT_EQ(calls, 120);
  EXPECT_EQ(rasterizer.statistics().written, static_cast<uint64_t>(accepted));
  EXPECT_EQ(rasterizer.statistics().fragments, static_cast<uint64_t>(offered + 120));
  rasterizer.reset_statistics();
  EXPECT_EQ(rasterizer.statistics().triangles, 0u);
  EXPECT_EQ(rasterizer.statistics().fragments, 0u);
}

TEST(Raster, RegionDrawingEqualsTheSamePixelsOfAFullDraw) {
  // Random triangles in perspective (some crossing the near plane) at distinct depths, drawn
  // with the depth test into the full image and into regions; every region holds the same
  // pixels: the same triangle, and the same depth and varyings (bit for bit in full-width bands).
  const ViewSetup scene;
  const int width = scene.camera.width(), height = scene.camera.height();
  Pcg32 random(3, 5);
  std::vector<std::array<Vec3, 3>> triangles;
  for (int i = 0; i < 40; ++i) {
    const Vec3 centre{4 * random.next_double() - 2, 3 * random.next_double() - 1.5,
                      4.5 - 9 * random.next_double()};
    std::array<Vec3, 3> t;
    for (Vec3& p : t)
      p = centre + Vec3{3 * random.next_double() - 1.5, 3 * random.next_double() - 1.5,
                        0.6 * random.next_double() - 0.3};
    triangles.push_back(t);
  }
  struct Pixel {
    int id = -1;
    double depth = kInfinity, varying = 0;
  };
  const auto draw = [&](int x0, int y0, int x1, int y1) {
    Rasterizer rasterizer(width, height);
    rasterizer.set_region(x0, y0, x1, y1);
    std::vector<Pixel> pixels(static_cast<std::size_t>(width * height));
    for (std::size_t i = 0; i < triangles.size(); ++i)
      rasterizer.draw_triangle(scene.vertex(triangles[i][0]), scene.vertex(triangles[i][1]),
                               scene.vertex(triangles[i][2]), 3, [&](const Fragment& f) {
                                 EXPECT_TRUE(f.x >= x0 && f.x < x1 && f.y >= y0 && f.y < y1);
                                 pixels[static_cast<std::size_t>(f.y * width + f.x)] = {
                                     static_cast<int>(i), f.depth, f.varyings[0]};
                                 return true;
                               });
    return pixels;
  };
  const std::vector<Pixel> full = draw(0, 0, width, height);
  int covered = 0;
  for (const Pixel& p : full) covered += p.id >= 0;
  EXPECT_GT(covered, width * height / 3);
  struct Region {
    int x0, y0, x1, y1;
  };
  for (const Region& r :
       {Region{0, 0, width, 7}, Region{0, 13, width, 41}, Region{0, 59, width, 60}, Region{17, 9, 53, 44},
        Region{1, 0, 2, 60}, Region{40, 30, 80, 60}, Region{5, 5, 5, 9}}) {
    const bool band = r.x0 == 0 && r.x1 == width;
    const std::vector<Pixel> part = draw(r.x0, r.y0, r.x1, r.y1);
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        const std::size_t i = static_cast<std::size_t>(y * width + x);
        const bool inside = x >= r.x0 && x < r.x1 && y >= r.y0 && y < r.y1;
        ASSERT_EQ(part[i].id, inside ? full[i].id : -1) << x << "," << y;
        if (!inside || full[i].id < 0) continue;
        if (band) {
          EXPECT_EQ(part[i].depth, full[i].depth);
          EXPECT_EQ(part[i].varying, full[i].varying);
        } else {
          EXPECT_NEAR(part[i].depth, full[i].depth, 1e-12);
          EXPECT_NEAR(part[i].varying, full[i].varying, 1e-12);
        }
      }
  }
}

TEST(Raster, RejectsBadArguments) {
  EXPECT_THROW(Rasterizer(0, 4), std::invalid_argument);
  EXPECT_THROW(Rasterizer(4, -1), std::invalid_argument);
  Rasterizer rasterizer(8, 4);
  EXPECT_THROW(rasterizer.set_region(0, 0, 9, 4), std::invalid_argument);
  EXPECT_THROW(rasterizer.set_region(3, 0, 2, 4), std::invalid_argument);
  EXPECT_THROW(rasterizer.set_region(-1, 0, 2, 4), std::invalid_argument);
  rasterizer.set_region(2, 1, 6, 3);
  EXPECT_EQ(rasterizer.depth_at(2, 1), kInfinity);
  EXPECT_THROW(rasterizer.depth_at(1, 1), std::out_of_range);
  EXPECT_THROW(rasterizer.depth_at(2, 3), std::out_of_range);
  const RasterVertex v = screen_vertex(1, 1, 8, 4);
  EXPECT_THROW(rasterizer.draw_triangle(v, v, v, kMaxVaryings + 1, [](const Fragment&) { return true; }),
               std::invalid_argument);
  EXPECT_THROW(rasterizer.draw_triangle(v, v, v, -1, [](const Fragment&) { return true; }),
               std::invalid_argument);
}

}  // namespace
}  // namespace candela
