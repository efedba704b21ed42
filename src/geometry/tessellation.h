// What the shapes' tessellate overrides share (SPEC §9 the rasterizer, §10 radiosity meshing):
// appending to a TriangleMesh without zero-area triangles, points around a circle, and the
// (u, v) grid of the shapes of revolution (sphere, cylinder, cone, disc, torus).
//
// Conventions, the same for every shape:
// - The surface's own uv goes with every corner (TriangleMesh::corner_uvs), so a texture looks
//   the same rasterized and ray traced. Corner uvs are per triangle, so a vertex on a seam is
//   one vertex, and only the corners on either side of the seam differ (u = 1 on the triangles
//   before the seam, u = 0 after it): nothing wraps backwards and the mesh stays connected.
// - Triangles are counter-clockwise about dpdu × dpdv, which every shape documents as its
//   geometric normal side (outward for closed shapes, the declared side for flat ones).
// - Area-true: a curved surface's triangles cover the surface's own area. Vertices on
//   the surface make an inscribed polyhedron with less area (a disc 2.55 % less at 16 segments, a
//   sphere 3.2 %), so a radiosity emitter would send less power and every form factor toward it
//   would be smaller; the curved shapes move their points away from the centre (the sphere, the
//   disc) or the axis (cylinder, cone, the torus's tube) by the one factor that gives the area back
//   (area_true_scale). By Cauchy's formula a convex body's mean projected area is a quarter of its
//   surface area, so the solid angle it subtends is right on average too.
// - A triangle whose cross(p1 - p0, p2 - p0) is exactly zero is never emitted (it is never hit
//   either, see MeshTriangle), nor is a vertex no emitted triangle uses. Vertices of one shape
//   at exactly the same position are one vertex (a cylinder's rims are shared by its side and
//   caps), so closed shapes are closed by index, not only by position.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <stdexcept>
#include <vector>

#include "geometry/shape.h"
#include "geometry/triangle_mesh.h"
#include "math/constants.h"

namespace candela {

// settings.segments raised to the minimum of 3 divisions of a full turn.
inline int turn_divisions(const TessellationSettings& settings) {
  return std::max(3, settings.segments);
}

// Appends triangles to a mesh that may already hold other shapes' triangles. Vertices are
// candidates, welded by exact position, until a triangle uses them: only then do they enter
// mesh.positions, so a shape whose triangles are all degenerate leaves the mesh untouched.
// Made without a mesh it only measures: the area of the triangles it is given (area_true_scale's
// trial builds), without welding or storing anything.
class MeshAppender {
 public:
  MeshAppender() = default;
  // Corner normals are the caller's (compute_corner_normals once every shape is in, SPEC §9):
  // a mesh that already has them is a std::logic_error. A mesh whose triangles have no corner
  // uvs gets the default ones written out ((0,0), (1,0), (1,1), which mean the same), so that
  // the appended triangles can carry theirs. Throws std::invalid_argument when corner_uvs is
  // neither empty nor one entry per triangle.
  explicit MeshAppender(TriangleMesh& mesh) : mesh_(&mesh) {
    if (!mesh.corner_normals.empty())
      throw std::logic_error("tessellate appends to meshes without corner normals; compute them afterwards");
    if (mesh.corner_uvs.empty()) {
      mesh.corner_uvs.assign(mesh.triangles.size(), kDefaultCornerUvs);
    } else if (mesh.corner_uvs.size() != mesh.triangles.size()) {
      throw std::invalid_argument("mesh corner uvs do not match its triangles");
    }
  }

  // A candidate vertex, the same id for the same position (-0 and +0 alike); the id is this
  // appender's, not an index into the mesh.
  uint32_t vertex(const Vec3& position) {
    if (!mesh_) {  // measuring: no welding (a weld only ever removes zero-area triangles)
      candidates_.push_back(position);
      return static_cast<uint32_t>(candidates_.size() - 1);
    }
    const auto [it, inserted] = ids_.emplace(std::array<double, 3>{position.x, position.y, position.z},
                                             static_cast<uint32_t>(candidates_.size()));
    if (inserted) {
      candidates_.push_back(position);
      mesh_index_.push_back(kNotInMesh);
    }
    return it->second;
  }
  const Vec3& position(uint32_t vertex) const { return candidates_[vertex]; }

  // Appends the triangle (vertex ids from vertex()) with its corner uvs, unless its corners
  // span exactly zero area.
  void triangle(const std::array<uint32_t, 3>& corners, const std::array<Vec2, 3>& uvs) {
    const Vec3& p0 = candidates_[corners[0]];
    const Vec3 face_cross = cross(candidates_[corners[1]] - p0, candidates_[corners[2]] - p0);
    if (!(length_squared(face_cross) > 0)) return;
    area_ += 0.5 * length(face_cross);
    if (!mesh_) return;
    std::array<uint32_t, 3> indices;
    for (int k = 0; k < 3; ++k) indices[k] = mesh_index(corners[k]);
    mesh_->triangles.push_back(indices);
    mesh_->corner_uvs.push_back(uvs);
  }
  // The area of the triangles appended so far.
  double area() const { return area_; }

 private:
  static constexpr uint32_t kNotInMesh = std::numeric_limits<uint32_t>::max();

  uint32_t mesh_index(uint32_t vertex) {
    if (mesh_index_[vertex] == kNotInMesh) {
      if (mesh_->positions.size() >= kNotInMesh) throw std::length_error("mesh has too many vertices");
      mesh_index_[vertex] = static_cast<uint32_t>(mesh_->positions.size());
      mesh_->positions.push_back(candidates_[vertex]);
    }
    return mesh_index_[vertex];
  }

  TriangleMesh* mesh_ = nullptr;  // null: measuring
  double area_ = 0;
  std::map<std::array<double, 3>, uint32_t> ids_;
  std::vector<Vec3> candidates_;
  std::vector<uint32_t> mesh_index_;
};

// The scale ≥ 1 by which build(scale, out) — a shape appending its triangles with its points
// moved away from its centre or axis by `scale` — covers target_area, the analytic surface's
// (see the area-true convention above); the area must grow with the scale. 1 when
// settings.area_true is off, when the triangles at scale 1 already cover it (a flat shape) or when
// target_area is not a positive number. The trial builds only measure (MeshAppender without a
// mesh). The first guess, √(target / area at 1), is the answer when the area goes as scale² (a
// sphere, a disc); otherwise a bracketed secant (the Illinois rule) takes a few more, to 1e-13.
template <typename Build>
double area_true_scale(const TessellationSettings& settings, double target_area, const Build& build) {
  if (!settings.area_true || !(target_area > 0) || !std::isfinite(target_area)) return 1;
  const auto excess_at = [&](double scale) {  // area over target, relative
    MeshAppender measure;
    build(scale, measure);
    return measure.area() / target_area - 1;
  };
  double low = 1, low_excess = excess_at(1);
  if (!(low_excess < 0) || !(low_excess > -1)) return 1;
  double high = 1 / std::sqrt(1 + low_excess), high_excess = excess_at(high);
  for (int k = 0; k < 64 && high_excess < 0; ++k) {
    low = high, low_excess = high_excess;
    high *= 1.5, high_excess = excess_at(high);
  }
  constexpr double kTolerance = 1e-13;
  if (std::fabs(high_excess) <= kTolerance) return high;
  // The secant runs on weighted excesses (Illinois); the ends' true ones decide what is returned.
  double low_true = low_excess, high_true = high_excess;
  int kept = 0;  // which end the last step replaced: −1 low, +1 high
  for (int k = 0; k < 200; ++k) {
    double scale = high - high_excess * (high - low) / (high_excess - low_excess);
    if (!(scale > low && scale < high)) scale = 0.5 * (low + high);
    const double excess = excess_at(scale);
    if (std::fabs(excess) <= kTolerance) return scale;
    if (excess < 0) {
      low = scale, low_excess = low_true = excess;
      if (kept == -1) high_excess *= 0.5;  // Illinois: the end kept twice weighs half
      kept = -1;
    } else {
      high = scale, high_excess = high_true = excess;
      if (kept == 1) low_excess *= 0.5;
      kept = 1;
    }
    if (high - low <= kTolerance * high) break;
  }
  return std::fabs(low_true) < std::fabs(high_true) ? low : high;
}

// (cos, sin) of 2π k / divisions for k in [0, divisions). Every shape takes its angles from
// this one table, so a point that two parts share (a cylinder's rim on the side and on the
// cap) is computed by the same operations and is bit-identical in both.
inline std::vector<Vec2> unit_circle(int divisions) {
  std::vector<Vec2> circle(divisions);
  for (int k = 0; k < divisions; ++k) {
    const double angle = 2 * kPi * k / divisions;
    circle[k] = {std::cos(angle), std::sin(angle)};
  }
  circle[0] = {1, 0};
  return circle;
}

// The points center + radius (x_axis cos φ_k + y_axis sin φ_k) at the angles of circle, in
// the order of increasing φ, or of decreasing φ (k = 0, n-1, n-2, ...) when clockwise. A zero
// radius gives the centre every time (a pole or an apex: append_revolution_grid then makes it
// one vertex).
inline std::vector<Vec3> circle_points(const Vec3& center, const Vec3& x_axis, const Vec3& y_axis,
                                       double radius, const std::vector<Vec2>& circle,
                                       bool clockwise = false) {
  const std::size_t divisions = circle.size();
  std::vector<Vec3> points(divisions);
  for (std::size_t k = 0; k < divisions; ++k) {
    const Vec2& angle = circle[clockwise ? (divisions - k) % divisions : k];
    points[k] = center + (x_axis * angle.x + y_axis * angle.y) * radius;
  }
  return points;
}

// The (u, v) grid of a shape of revolution: rings[r][c] is the point at u = c / columns,
// v = r / (rings.size() - 1), for columns = rings[r].size() (the same in every ring), c in
// [0, columns): u wraps, column `columns` being column 0 again. With wrap_rings (the torus)
// v wraps too: v = r / rings.size() and ring rings.size() is ring 0.
//
// Each cell (c, r) becomes (c, r) (c+1, r) (c+1, r+1) and (c, r) (c+1, r+1) (c, r+1), which is
// counter-clockwise about dpdu × dpdv. Corner uvs are (c / columns, r / rings): the last column
// gets u = 1, not 0. A ring whose points all coincide (a sphere's pole, a cone's apex, a disc's
// centre) is one vertex and each cell next to it one triangle, its apex corner at the cell's
// middle u (the direction the triangle actually covers).
inline void append_revolution_grid(const std::vector<std::vector<Vec3>>& rings, bool wrap_rings,
                                   MeshAppender& out) {
  const std::size_t ring_count = rings.size();
  const std::size_t columns = rings[0].size();
  const std::size_t bands = wrap_rings ? ring_count : ring_count - 1;
  // Vertex ids per ring (a collapsed ring's are all one id, the appender welding them).
  std::vector<std::vector<uint32_t>> ids(ring_count);
  std::vector<bool> collapsed(ring_count);
  for (std::size_t r = 0; r < ring_count; ++r) {
    const std::vector<Vec3>& ring = rings[r];
    collapsed[r] = std::all_of(ring.begin(), ring.end(), [&](const Vec3& p) { return p == ring[0]; });
    for (const Vec3& p : ring) ids[r].push_back(out.vertex(p));
  }
  const double column_count = static_cast<double>(columns);
  const double band_count = static_cast<double>(bands);
  for (std::size_t r = 0; r < bands; ++r) {
    const std::size_t next_ring = (r + 1) % ring_count;
    const double v0 = r / band_count, v1 = (r + 1) / band_count;
    for (std::size_t c = 0; c < columns; ++c) {
      const std::size_t next_column = (c + 1) % columns;
      const double u0 = c / column_count, u1 = (c + 1) / column_count, u_middle = (c + 0.5) / column_count;
      const uint32_t a = ids[r][c], b = ids[r][next_column];
      const uint32_t d = ids[next_ring][c], e = ids[next_ring][next_column];
      if (collapsed[r] && collapsed[next_ring]) continue;
      if (collapsed[r]) {
        out.triangle({a, e, d}, {Vec2{u_middle, v0}, Vec2{u1, v1}, Vec2{u0, v1}});
      } else if (collapsed[next_ring]) {
        out.triangle({a, b, e}, {Vec2{u0, v0}, Vec2{u1, v0}, Vec2{u_middle, v1}});
      } else {
        out.triangle({a, b, e}, {Vec2{u0, v0}, Vec2{u1, v0}, Vec2{u1, v1}});
        out.triangle({a, e, d}, {Vec2{u0, v0}, Vec2{u1, v1}, Vec2{u0, v1}});
      }
    }
  }
}

// A truncated cone about the axis from base_center toward axis·height (a cylinder when both
// radii are equal): the side as one band — v = z / height — and, when capped, the caps whose
// radius is > 0 — v = 0 on the rim, 1 at the centre; the base cap's u runs clockwise about the
// axis (counter-clockwise seen from outside), hence its reversed ring. Every rim point is
// computed by circle_points from the same centre, so side and caps share them bit for bit, and
// a zero radius makes its ring one apex vertex. x_axis, y_axis: the shape's own frame axes.
inline void append_truncated_cone(const Vec3& base_center, const Vec3& axis, double height,
                                  const Vec3& x_axis, const Vec3& y_axis, double base_radius,
                                  double cap_radius, bool capped, const std::vector<Vec2>& circle,
                                  MeshAppender& out) {
  const Vec3 top_center = base_center + axis * height;
  append_revolution_grid({circle_points(base_center, x_axis, y_axis, base_radius, circle),
                          circle_points(top_center, x_axis, y_axis, cap_radius, circle)},
                         /*wrap_rings=*/false, out);
  if (!capped) return;
  if (cap_radius > 0)
    append_revolution_grid({circle_points(top_center, x_axis, y_axis, cap_radius, circle),
                            circle_points(top_center, x_axis, y_axis, 0, circle)},
                           /*wrap_rings=*/false, out);
  if (base_radius > 0)
    append_revolution_grid(
        {circle_points(base_center, x_axis, y_axis, base_radius, circle, /*clockwise=*/true),
         circle_points(base_center, x_axis, y_axis, 0, circle, /*clockwise=*/true)},
        /*wrap_rings=*/false, out);
}

}  // namespace candela
