// Tests of the vertex radiosities of 000 §6.5 (radiosity/vertex_radiosity.h).
#include "radiosity/vertex_radiosity.h"

#include <gtest/gtest.h>

#include <functional>

namespace candela {
namespace {

RadiositySurface triangle(const Vec3& a, const Vec3& b, const Vec3& c, uint32_t object) {
  RadiositySurface s;
  s.corners = {a, b, c};
  s.centroid = (a + b + c) * (1.0 / 3);
  s.normal = normalize(cross(b - a, c - a));
  s.area = 0.5 * length(cross(b - a, c - a));
  s.object = object;
  return s;
}

// An n × n grid of unit squares in z = 0 starting at x = x0, each split along its diagonal
// (i, j)–(i+1, j+1), with element radiosities field(centroid).
void add_grid(int n, double x0, uint32_t object, const std::function<double(const Vec3&)>& field,
              std::vector<RadiositySurface>& elements, std::vector<Color>& radiosity) {
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const Vec3 p00(x0 + i, j, 0), p10(x0 + i + 1, j, 0), p11(x0 + i + 1, j + 1, 0), p01(x0 + i, j + 1, 0);
      for (const RadiositySurface& s : {triangle(p00, p10, p11, object), triangle(p00, p11, p01, object)}) {
        elements.push_back(s);
        radiosity.push_back(Color(field(s.centroid)));
      }
    }
}

TEST(VertexRadiosity, LinearFieldIsReproducedAtInteriorAndEdgeVertices) {
  const auto field = [](const Vec3& p) { return 1 + 0.3 * p.x + 0.2 * p.y; };
  std::vector<RadiositySurface> elements;
  std::vector<Color> radiosity;
  const int n = 5;
  add_grid(n, 0, 0, field, elements, radiosity);
  const VertexRadiosity vertices = compute_vertex_radiosity(elements, radiosity);
  ASSERT_EQ(vertices.positions.size(), std::size_t((n + 1) * (n + 1)));
  int interior = 0, edge = 0;
  for (std::size_t v = 0; v < vertices.positions.size(); ++v) {
    const Vec3& p = vertices.positions[v];
    const bool on_x_side = p.x == 0 || p.x == n, on_y_side = p.y == 0 || p.y == n;
    if (on_x_side && on_y_side) continue;  // corners: checked below
    EXPECT_EQ(vertices.kind[v], on_x_side || on_y_side ? VertexKind::boundary : VertexKind::interior);
    ++(on_x_side || on_y_side ? edge : interior);
    EXPECT_NEAR(vertices.radiosity[v].r, field(p), 1e-12) << p.x << ", " << p.y;
  }
  EXPECT_EQ(interior, (n - 1) * (n - 1));
  EXPECT_EQ(edge, 4 * (n - 1));
  // The corners on the grid's diagonals have an interior neighbour (B_a = 2B_1 − B_e, exact);
  // the other two have none (000 §6.5, Figure 58b) and get the mean of their one element.
  for (std::size_t v = 0; v < vertices.positions.size(); ++v) {
    const Vec3& p = vertices.positions[v];
    if ((p.x == 0 && p.y == 0) || (p.x == n && p.y == n)) {
      EXPECT_EQ(vertices.kind[v], VertexKind::boundary);
      EXPECT_NEAR(vertices.radiosity[v].r, field(p), 1e-12);
    } else if ((p.x == n && p.y == 0) || (p.x == 0 && p.y == n)) {
      EXPECT_EQ(vertices.kind[v], VertexKind::isolated_boundary);
    }
  }
}

TEST(VertexRadiosity, ExtrapolationIsClampedAtZero) {
  const auto field = [](const Vec3& p) { return p.x - 0.2; };  // ≥ 0.13 at every centroid
  std::vector<RadiositySurface> elements;
  std::vector<Color> radiosity;
  add_grid(4, 0, 0, field, elements, radiosity);
  const VertexRadiosity vertices = compute_vertex_radiosity(elements, radiosity);
  for (std::size_t v = 0; v < vertices.positions.size(); ++v) {
    const Vec3& p = vertices.positions[v];
    EXPECT_GE(vertices.radiosity[v].r, 0);
    if (p.x == 0 && p.y > 0 && p.y < 4) {
      EXPECT_EQ(vertices.radiosity[v].r, 0);  // −0.2 clamped
    }
    if (p.x == 1 && p.y > 0 && p.y < 4) {
      EXPECT_NEAR(vertices.radiosity[v].r, 0.8, 1e-12);
    }
  }
}

TEST(VertexRadiosity, VerticesAreNotSharedAcrossObjects) {
  // Two coplanar grids meeting along x = 3, one dark (object 0), one bright (object 1).
  std::vector<RadiositySurface> elements;
  std::vector<Color> radiosity;
  add_grid(
      3, 0, 0, [](const Vec3&) { return 1.0; }, elements, radiosity);
  add_grid(
      3, 3, 1, [](const Vec3&) { return 5.0; }, elements, radiosity);
  const VertexRadiosity vertices = compute_vertex_radiosity(elements, radiosity);
  EXPECT_EQ(vertices.positions.size(), std::size_t(2 * 16));
  for (std::size_t v = 0; v < vertices.positions.size(); ++v)
    EXPECT_DOUBLE_EQ(vertices.radiosity[v].r, vertices.object[v] == 0 ? 1.0 : 5.0);
  for (std::size_t q = 0; q < elements.size(); ++q)
    for (const uint32_t v : vertices.element_vertices[q]) EXPECT_EQ(vertices.object[v], elements[q].object);
}

TEST(VertexRadiosity, TJunctionVertexIsInterior) {
  // A unit square of object 0 as two triangles, its right neighbour split so that the vertex
  // (1, 0.5) hangs on the square's edge x = 1: that edge is no boundary.
  std::vector<RadiositySurface> elements{
      triangle({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, 0), triangle({0, 0, 0}, {1, 1, 0}, {0, 1, 0}, 0),
      triangle({1, 0, 0}, {2, 0, 0}, {1, 0.5, 0}, 0), triangle({2, 0, 0}, {2, 1, 0}, {1, 0.5, 0}, 0),
      triangle({1, 0.5, 0}, {2, 1, 0}, {1, 1, 0}, 0)};
  const std::vector<Color> radiosity(elements.size(), Color(2.0));
  const VertexRadiosity vertices = compute_vertex_radiosity(elements, radiosity);
  for (std::size_t v = 0; v < vertices.positions.size(); ++v) {
    const Vec3& p = vertices.positions[v];
    if (p.x == 1 && p.y == 0.5) {
      EXPECT_EQ(vertices.kind[v], VertexKind::interior);
    }
    EXPECT_DOUBLE_EQ(vertices.radiosity[v].r, 2.0);
  }
}

TEST(VertexRadiosity, BoxFacesKeepTheirOwnVerticesAtACrease) {
  // Two faces of one object meeting at a right angle: no vertex is shared.
  std::vector<RadiositySurface> elements{triangle({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, 0),
                                         triangle({0, 0, 0}, {0, 0, 1}, {1, 0, 0}, 0)};
  const VertexRadiosity vertices = compute_vertex_radiosity(elements, {Color(1.0), Color(3.0)});
  EXPECT_EQ(vertices.positions.size(), std::size_t(6));
}

TEST(VertexRadiosity, SizeMismatchThrows) {
  EXPECT_THROW(compute_vertex_radiosity({triangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 0)}, {}),
               std::invalid_argument);
}

TEST(VertexRadiosity, HiddenElementsKeepTheirOwnVerticesAndLeaveTheOthersAlone) {
  // A linear field on a 4 × 4 grid; two elements in the middle are "hidden" (they lie under
  // another surface) and black. Left in, they would darken the vertices around them; left out,
  // the other elements' vertices are what the grid without those two gives, and each hidden
  // element shows its own flat value.
  const auto field = [](const Vec3& p) { return 1 + 0.3 * p.x + 0.2 * p.y; };
  std::vector<RadiositySurface> elements;
  std::vector<Color> radiosity;
  add_grid(4, 0, 0, field, elements, radiosity);
  std::vector<uint8_t> hidden(elements.size(), 0);
  for (const std::size_t q : {std::size_t{10}, std::size_t{11}}) hidden[q] = 1, radiosity[q] = Color(0.0);
  const VertexRadiosity with_hidden = compute_vertex_radiosity(elements, radiosity, hidden);
  std::vector<RadiositySurface> visible;
  std::vector<Color> visible_radiosity;
  for (std::size_t q = 0; q < elements.size(); ++q)
    if (!hidden[q]) visible.push_back(elements[q]), visible_radiosity.push_back(radiosity[q]);
  const VertexRadiosity without = compute_vertex_radiosity(visible, visible_radiosity);
  ASSERT_EQ(with_hidden.element_vertices.size(), elements.size());
  std::size_t next = 0;
  for (std::size_t q = 0; q < elements.size(); ++q) {
    for (std::size_t k = 0; k < 3; ++k) {
      const Color got = with_hidden.radiosity[with_hidden.element_vertices[q][k]];
      EXPECT_EQ(with_hidden.positions[with_hidden.element_vertices[q][k]], elements[q].corners[k]);
      if (hidden[q]) {
        EXPECT_EQ(got.r, 0.0);
      } else {
        EXPECT_EQ(got.r, without.radiosity[without.element_vertices[next][k]].r);
        EXPECT_GT(got.r, 0.5);  // never pulled toward the hidden black
      }
    }
    if (!hidden[q]) ++next;
  }
  EXPECT_EQ(with_hidden.positions.size(), without.positions.size() + 6);
  // Empty flags: the plain computation.
  const VertexRadiosity plain = compute_vertex_radiosity(elements, radiosity, {});
  EXPECT_EQ(plain.positions.size(), compute_vertex_radiosity(elements, radiosity).positions.size());
  EXPECT_THROW(compute_vertex_radiosity(elements, radiosity, std::vector<uint8_t>(3, 0)),
               std::invalid_argument);
}

}  // namespace
}  // namespace candela

namespace candela {
namespace {

// A T-junction vertex (the corner of two small elements inside the edge of a larger one)
// takes the radiosity the larger element interpolates there, so Gouraud shading has no crack
// along that edge. The left unit square is two elements; the right one four, whose corner (1, 0.5)
// lies inside the left square's edge (1, 0)–(1, 1). Averaging the elements at that vertex alone
// (the larger one among them) would give it another value than the left element shows there.
TEST(VertexRadiosity, TJunctionVerticesLieOnTheLargerElementsInterpolation) {
  const auto square = [](double x0, double y0, double size, uint32_t object, double value,
                         std::vector<RadiositySurface>& elements, std::vector<Color>& radiosity) {
    const Vec3 p00(x0, y0, 0), p10(x0 + size, y0, 0), p11(x0 + size, y0 + size, 0), p01(x0, y0 + size, 0);
    for (const RadiositySurface& s : {triangle(p00, p10, p11, object), triangle(p00, p11, p01, object)}) {
      elements.push_back(s);
      radiosity.push_back(Color(value));
    }
  };
  std::vector<RadiositySurface> elements;
  std::vector<Color> radiosity;
  square(0, 0, 1, 0, 1, elements, radiosity);
  square(1, 0, 0.5, 0, 3, elements, radiosity);
  square(1, 0.5, 0.5, 0, 5, elements, radiosity);
  square(1.5, 0, 0.5, 0, 4, elements, radiosity);
  square(1.5, 0.5, 0.5, 0, 6, elements, radiosity);
  const VertexRadiosity vertices = compute_vertex_radiosity(elements, radiosity);
  const auto vertex_at = [&](double x, double y) {
    for (std::size_t v = 0; v < vertices.positions.size(); ++v)
      if (vertices.positions[v].x == x && vertices.positions[v].y == y) return v;
    ADD_FAILURE() << "no vertex at " << x << ", " << y;
    return std::size_t{0};
  };
  const double bottom = vertices.radiosity[vertex_at(1, 0)].g, top = vertices.radiosity[vertex_at(1, 1)].g;
  EXPECT_NE(bottom, top);
  EXPECT_NEAR(vertices.radiosity[vertex_at(1, 0.5)].g, 0.5 * (bottom + top), 1e-12);
  // A vertex inside an edge of the small ones is an ordinary interior vertex.
  EXPECT_EQ(vertices.kind[vertex_at(1.5, 0.5)], VertexKind::interior);
}

}  // namespace
}  // namespace candela
