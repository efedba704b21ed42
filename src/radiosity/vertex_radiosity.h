// Vertex radiosities for smooth (Gouraud) display of a radiosity solution (000 §6.5, SPEC §10
// "Display"): the element radiosities extrapolated to the elements' corners.
//
// Vertices are shared by position within one object only (never across objects, which would leak
// light across a corner), and within an object only between elements whose normals differ by at
// most 45° (so a box's faces keep their own vertices at its edges, while a tessellated sphere's
// facets share theirs).
//
// The seed's rules (000 §6.5, Figure 58a), stated for a grid of quadrilateral elements:
//   interior vertex e   B_e = (B_1 + B_2 + B_3 + B_4) / 4: the mean of the adjacent elements;
//   edge vertex b       the midpoint X of b and the nearest interior vertex e has the radiosity
//                       (B_b + B_e)/2 = (B_1 + B_2)/2, with 1 and 2 the elements sharing the edge
//                       b–e, so B_b = B_1 + B_2 − B_e;
//   corner vertex a     (B_a + B_e)/2 = B_1, with 1 the one element holding both a and e, so
//                       B_a = 2 B_1 − B_e.
// Our reading for the triangular elements of the mesh: a vertex is on the boundary when one of
// its edges belongs to one element only (an edge whose midpoints are other vertices of the same
// surface — a T-junction of the bisection — is not a boundary). For a boundary vertex v we take
// the nearest interior vertex e joined to v by an element edge (ties: the lower vertex index) and
// the elements S holding both v and e; then both of the seed's rules read
//     B_v = 2 · mean_{S} B − B_e
// (two elements: B_1 + B_2 − B_e; one: 2B_1 − B_e). On a regular triangulated grid the two
// elements of the edge v–e form a parallelogram whose centroids average to the midpoint of v–e, so
// a linear radiosity field is reproduced exactly. A boundary vertex with no interior neighbour
// (the seed's Figure 58b: "there seems to be no general formula") gets the mean of its adjacent
// elements. Every result is clamped at 0 per channel.
//
// No cracks (SPEC §10.1): where the corner of smaller elements lies inside the edge of a
// larger one (a T-junction of the bisection or of hierarchical radiosity's quadtrees), that vertex
// takes the radiosity the larger element interpolates there, (1 − t) B_a + t B_b along its edge
// a–b, so the Gouraud field is continuous across levels.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "math/vector.h"
#include "radiosity/radiosity_mesh.h"

namespace candela {

enum class VertexKind : uint8_t { interior, boundary, isolated_boundary };

struct VertexRadiosity {
  std::vector<Vec3> positions;
  std::vector<uint32_t> object;  // the object each vertex belongs to
  std::vector<VertexKind> kind;  // isolated_boundary: a boundary vertex with no interior neighbour
  std::vector<Color> radiosity;  // B at each vertex, ≥ 0
  // The vertices of each element's corners (same order as RadiositySurface::corners).
  std::vector<std::array<uint32_t, 3>> element_vertices;
};

// The vertex radiosities of `elements` (one radiosity per element). Throws std::invalid_argument
// when the sizes differ.
VertexRadiosity compute_vertex_radiosity(const std::vector<RadiositySurface>& elements,
                                         const std::vector<Color>& element_radiosity);

// The same over the elements with hidden[q] == 0 only; every hidden element (one lying against
// another surface, which sees nothing and receives nothing: its radiosity says nothing about its
// visible neighbours') gets three vertices of its own carrying its flat radiosity. element_vertices
// keeps the order of elements. hidden may be empty (nothing hidden).
VertexRadiosity compute_vertex_radiosity(const std::vector<RadiositySurface>& elements,
                                         const std::vector<Color>& element_radiosity,
                                         const std::vector<uint8_t>& hidden);

}  // namespace candela
