// Form factors by the hemicube (000 §6.4; Cohen and Greenberg 1985): from a point of a patch
// (its centre) with a normal and a tangent, every element of the scene is drawn into the item
// buffers of the five hemicube faces (raster/hemicube_views.h, raster/item_buffer.h: the
// z-buffer keeps the nearest element per cell, 000 eq. 6-10's visibility H), and the delta form
// factors (radiosity/delta_form_factors.h) of the cells where an element is seen add up to the
// form factor from the point to that element, F_j = Σ_q ΔF_q.
//
// What is computed: the row F_{dA→j}, j = 0 … element_count − 1, from the differential area at
// the point (the seed's hemicube approximation of F_ij, eq. 6-10). Averaging rows over points of
// a patch weighted by area gives the substructured F_ij = (1/A_i) Σ_k A_k F_{k→j} (000 eq. 6-19).
//
// Conventions:
// - Geometry: triangles in world space, each with the id of the element it belongs to, its front
//   side the one its corners wind counter-clockwise around. Surfaces are one-sided: a triangle
//   seen from behind is drawn (it hides what is behind it) with the id kBackFace, and its cells
//   add to no element (element ids must lie below kBackFace). The source's own triangles (those of
//   source_element) are skipped, so F_{source→source} = 0, as the seed's F_ii.
// - Near and far planes: near = near_fraction × (the largest distance from the point to a
//   vertex of the mesh), far = 2 × that distance. The patch, which lies in the plane through the
//   point, and every coplanar neighbour are then never seen: behind the near plane of the top
//   face, and exactly on the boundary row between the upper and lower halves of a side face,
//   which covers no cell centre. Geometry closer to the point than the near plane is missed
//   (default near_fraction 1e-5).
// - Culling: triangles whose three corners lie on or below the plane through the point (n·(p −
//   centre) ≤ 0) cannot be seen and are not drawn; the rest are drawn once into each face (each
//   face transforms every corner once, by ItemBuffer::draw). Side faces draw only the upper half of their
//   rows (ItemBuffer::set_region).
// - Resources: the item buffers and scratch arrays are allocated once, by the constructor and
//   the first rows; later rows allocate nothing beyond growing the output row. An object is
//   used by one thread at a time: give each thread its own (they can share one
//   DeltaFormFactors table).
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "geometry/triangle_mesh.h"
#include "math/vector.h"
#include "radiosity/delta_form_factors.h"
#include "raster/item_buffer.h"

namespace candela {

// Scene geometry for form factors: a triangle mesh in world space and the element each
// triangle belongs to (elements 0 … element_count − 1; an element may span many triangles).
struct FormFactorGeometry {
  TriangleMesh mesh;
  std::vector<uint32_t> element_of_triangle;  // one per triangle of mesh
  uint32_t element_count = 0;
  // Per triangle (or empty: none): seen from behind it is not drawn at all — one side of a
  // two-sided surface, whose twin on the other side (wound the other way) hides what it hides.
  std::vector<uint8_t> hidden_from_behind;

  // Throws std::invalid_argument for an invalid mesh (TriangleMesh::validate), a count of
  // element ids other than one per triangle, or an id ≥ element_count.
  void validate() const;
};

// The id of no element: a row computed with it as the source skips no triangle.
inline constexpr uint32_t kNoElement = 0xFFFFFFFFu;
// The item id of a triangle seen from behind: it occludes, and nothing is added for it.
inline constexpr uint32_t kBackFace = 0xFFFFFFFEu;

class HemicubeFormFactors {
 public:
  static constexpr double kDefaultNearFraction = 1e-5;

  // A hemicube of the given resolution (even, ≥ 2: the top face is R × R cells, a side face
  // R × R/2 above the surface). Throws std::invalid_argument for a bad resolution or unless
  // 0 < near_fraction < 1.
  explicit HemicubeFormFactors(int resolution, double near_fraction = kDefaultNearFraction);
  // Shares a table of delta form factors (e.g. one per thread pool). Throws
  // std::invalid_argument for a null table or a bad near_fraction.
  explicit HemicubeFormFactors(std::shared_ptr<const DeltaFormFactors> delta_form_factors,
                               double near_fraction = kDefaultNearFraction);

  // Fills row (resized to geometry.element_count) with F from the differential area at centre,
  // facing normal, to every element; tangent orients the hemicube around the normal (any
  // vector not along the normal; see hemicube_face_axes). source_element's triangles are
  // skipped (kNoElement: none). The geometry's element ids and corner indices are checked
  // (std::invalid_argument) as the triangles are culled; positions are not (validate() them
  // once). Throws std::invalid_argument for a zero or non-finite normal or a non-finite centre.
  void compute_row(const FormFactorGeometry& geometry, const Vec3& center, const Vec3& normal,
                   const Vec3& tangent, uint32_t source_element, std::vector<double>& row);
  // The same, returning a new row.
  std::vector<double> row(const FormFactorGeometry& geometry, const Vec3& center, const Vec3& normal,
                          const Vec3& tangent, uint32_t source_element);

  int resolution() const { return delta_form_factors_->resolution(); }
  double near_fraction() const { return near_fraction_; }
  const DeltaFormFactors& delta_form_factors() const { return *delta_form_factors_; }
  // Triangles drawn (summed over faces) and cells covered by an element, since construction.
  uint64_t triangles_drawn() const { return triangles_drawn_; }
  uint64_t cells_covered() const { return cells_covered_; }

 private:
  // Adds the delta form factors of the covered cells of rows [0, rows) of the item buffer to
  // row_out by element id (every drawn id is an element below the row's size).
  void accumulate(const ItemBuffer& items, HemicubeFace face, int rows, double* row_out);

  std::shared_ptr<const DeltaFormFactors> delta_form_factors_;
  double near_fraction_;
  ItemBuffer top_items_;   // R × R, all of it drawn
  ItemBuffer side_items_;  // R × R, only rows 0 … R/2 − 1 (above the surface) drawn
  // Scratch kept between rows: the triangles that may be seen (corners relative to the
  // centre, for precision) and their element ids; the corner heights above the plane.
  TriangleMesh visible_;
  std::vector<uint32_t> visible_elements_;
  std::vector<double> corner_heights_;
  std::vector<double> delta_row_;  // one image row of delta form factors
  uint64_t triangles_drawn_ = 0;
  uint64_t cells_covered_ = 0;
};

// Σ_j row[j]: 1 in a closed scene (000 eq. 6-6), up to the hemicube's discretisation.
double row_sum(std::span<const double> row);

}  // namespace candela
