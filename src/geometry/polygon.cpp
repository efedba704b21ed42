#include "geometry/polygon.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "geometry/ear_clipping.h"
#include "geometry/flat_surface.h"
#include "geometry/surface_sampling.h"
#include "geometry/tessellation.h"
#include "math/constants.h"
#include "sampling/warps.h"

namespace candela {

void Polygon::refuse_crossing_edges() const {
  // A self-intersecting polygon (a pentagram drawn through its five points) has no one
  // fill rule: the ray test's crossing count leaves its centre empty (even-odd) while ear
  // clipping — raster, radiosity, sampling — filled a different shape. Such a polygon is refused:
  // every polygon accepted is simple, and every method sees the same one.
  const std::size_t count = projected_.size();
  for (std::size_t i = 0; i < count; ++i)
    for (std::size_t j = i + 2; j < count; ++j) {
      if (i == 0 && j == count - 1) continue;  // neighbours through the first vertex
      const Vec2 &a = projected_[i], &b = projected_[(i + 1) % count];
      const Vec2 &c = projected_[j], &d = projected_[(j + 1) % count];
      const double c_side = orientation(a, b, c), d_side = orientation(a, b, d);
      const double a_side = orientation(c, d, a), b_side = orientation(c, d, b);
      if (((c_side < 0 && d_side > 0) || (c_side > 0 && d_side < 0)) &&
          ((a_side < 0 && b_side > 0) || (a_side > 0 && b_side < 0)))
        throw std::invalid_argument("polygon edges " + std::to_string(i) + "–" +
                                    std::to_string((i + 1) % count) + " and " + std::to_string(j) + "–" +
                                    std::to_string((j + 1) % count) +
                                    " cross: a self-intersecting polygon has no one inside; split it into "
                                    "simple polygons (a star as its outline of 2n vertices)");
    }
}

Polygon::Polygon(std::vector<Vec3> vertices) : vertices_(std::move(vertices)) {
  const size_t count = vertices_.size();
  if (count < 3) throw std::invalid_argument("polygon needs at least 3 vertices");
  for (const Vec3& vertex : vertices_) {
    if (!is_finite(vertex)) throw std::invalid_argument("polygon vertices must be finite");
    bounds_.extend(vertex);
  }
  const double size = length(bounds_.diagonal());
  // Newell's method: twice the vector area, summed about the first vertex for accuracy.
  Vec3 area_vector;
  for (size_t i = 1; i + 1 < count; ++i)
    area_vector += cross(vertices_[i] - vertices_[0], vertices_[i + 1] - vertices_[0]);
  const double area_length = length(area_vector);
  if (!(area_length > 1e-12 * size * size)) throw std::invalid_argument("polygon has zero area");
  normal_ = area_vector / area_length;
  for (const Vec3& vertex : vertices_) {
    if (std::fabs(dot(vertex - vertices_[0], normal_)) > 1e-6 * size)
      throw std::invalid_argument("polygon vertices must be coplanar");
  }
  // 000 Figure 41: drop the coordinate where the normal is largest.
  const int dropped = max_dimension(abs(normal_));
  u_index_ = (dropped + 1) % 3;
  v_index_ = (dropped + 2) % 3;
  projected_.reserve(count);
  for (const Vec3& vertex : vertices_) projected_.push_back({vertex[u_index_], vertex[v_index_]});
  refuse_crossing_edges();
  // The uv frame along the first edge of non-zero length (within the plane).
  Vec3 edge;
  for (size_t i = 1; i < count && length_squared(edge) == 0; ++i) {
    edge = vertices_[i] - vertices_[0];
    edge -= normal_ * dot(edge, normal_);
  }
  u_axis_ = normalize(edge);
  v_axis_ = cross(normal_, u_axis_);
  Vec2 upper{-kInfinity, -kInfinity};
  uv_lower_ = {kInfinity, kInfinity};
  for (const Vec3& vertex : vertices_) {
    const double u = dot(vertex - vertices_[0], u_axis_), v = dot(vertex - vertices_[0], v_axis_);
    uv_lower_ = {std::min(uv_lower_.x, u), std::min(uv_lower_.y, v)};
    upper = {std::max(upper.x, u), std::max(upper.y, v)};
  }
  uv_extent_ = {upper.x - uv_lower_.x, upper.y - uv_lower_.y};
  // The triangles the polygon is sampled over (ear clipping handles concave polygons).
  TriangleMesh mesh;
  tessellate(TessellationSettings{}, mesh);
  std::vector<double> areas;
  for (const auto& triangle : mesh.triangles) {
    const std::array<Vec3, 3> corners{mesh.positions[triangle[0]], mesh.positions[triangle[1]],
                                      mesh.positions[triangle[2]]};
    const double triangle_area = 0.5 * length(cross(corners[1] - corners[0], corners[2] - corners[0]));
    if (!(triangle_area > 0)) continue;
    sample_triangles_.push_back(corners);
    areas.push_back(triangle_area);
    area_ += triangle_area;
  }
  triangle_choice_ = Distribution1D(std::move(areas));
}

bool Polygon::sample_area(const Vec2& u, SurfaceSample& sample) const {
  std::size_t index = 0;
  double probability = 0, remapped = 0;
  if (!triangle_choice_.sample_discrete(u.x, index, probability, &remapped)) return false;
  const std::array<Vec3, 3>& corners = sample_triangles_[index];
  const Vec2 b = square_to_uniform_triangle({remapped, u.y});
  sample.position = corners[0] * b.x + corners[1] * b.y + corners[2] * (1 - b.x - b.y);
  // The polygon's own normal, as intersect reports it (the triangles lie in its plane).
  sample.normal = normal_;
  sample.pdf = 1 / area_;
  return true;
}

double Polygon::pdf_area(const SurfaceHit&) const {
  return area_ > 0 ? 1 / area_ : 0;
}

bool Polygon::contains_projected(double u, double v) const {
  // 000 Figure 42b: translate so the hit point is the origin and count the edges crossing the
  // +u half-axis. A vertex with v = 0 is on the +v side (the axis is moved infinitesimally).
  bool inside = false;
  const size_t count = projected_.size();
  const Vec2* previous = &projected_[count - 1];
  for (size_t i = 0; i < count; ++i) {
    const Vec2& current = projected_[i];
    const double u0 = previous->x - u, v0 = previous->y - v;
    const double u1 = current.x - u, v1 = current.y - v;
    if ((v0 < 0) != (v1 < 0)) {  // the edge crosses the u axis
      if (u0 > 0 && u1 > 0) {
        inside = !inside;
      } else if (u0 > 0 || u1 > 0) {
        // Where the edge meets v = 0 (v1 != v0 since their signs differ).
        if (u0 - v0 * (u1 - u0) / (v1 - v0) > 0) inside = !inside;
      }
    }
    previous = &current;
  }
  return inside;
}

double Polygon::nearest_t(const Ray& ray) const {
  // 000 eq. 5-13: t = -(d + N.O) / N.D with d = -V0.N, written as N.(V0 - O) / N.D.
  const double t = plane_hit_distance(ray, vertices_[0], normal_);
  if (t == kInfinity) return kInfinity;
  const Vec3 point = ray.at(t);
  return contains_projected(point[u_index_], point[v_index_]) ? t : kInfinity;
}

bool Polygon::intersect(const Ray& ray, SurfaceHit& hit) const {
  const double t = nearest_t(ray);
  if (t == kInfinity) return false;
  fill_flat_hit(ray, t, normal_, hit);
  const Vec3 offset = hit.position - vertices_[0];
  hit.uv = {std::clamp((dot(offset, u_axis_) - uv_lower_.x) / uv_extent_.x, 0.0, 1.0),
            std::clamp((dot(offset, v_axis_) - uv_lower_.y) / uv_extent_.y, 0.0, 1.0)};
  hit.dpdu = u_axis_ * uv_extent_.x;
  hit.dpdv = v_axis_ * uv_extent_.y;
  return true;
}

bool Polygon::occluded(const Ray& ray) const {
  return nearest_t(ray) < kInfinity;
}

Bounds3 Polygon::bounds() const {
  return bounds_;
}

void Polygon::tessellate(const TessellationSettings&, TriangleMesh& mesh) const {
  MeshAppender out(mesh);
  // The vertices in the uv frame's axes (counter-clockwise about the normal, since Newell's
  // normal follows the vertex order), dropping repeated consecutive vertices.
  std::vector<uint32_t> vertex;
  std::vector<Vec2> plane, uv;
  std::vector<uint32_t> place;  // the first kept corner at the same point
  for (std::size_t i = 0; i < vertices_.size(); ++i) {
    const Vec3& position = vertices_[i];
    if (position == vertices_[(i + 1) % vertices_.size()]) continue;
    const Vec3 offset = position - vertices_[0];
    const Vec2 in_plane{dot(offset, u_axis_), dot(offset, v_axis_)};
    // As intersect: the bounding rectangle of the vertices in this frame is [0, 1]².
    uv.push_back({std::clamp((in_plane.x - uv_lower_.x) / uv_extent_.x, 0.0, 1.0),
                  std::clamp((in_plane.y - uv_lower_.y) / uv_extent_.y, 0.0, 1.0)});
    plane.push_back(in_plane);
    vertex.push_back(out.vertex(position));
    auto same = static_cast<uint32_t>(place.size());
    for (uint32_t k = 0; k < place.size(); ++k)
      if (out.position(vertex[k]) == position) {
        same = k;
        break;
      }
    place.push_back(same);
  }
  for (const auto& [a, b, c] : ear_clip(plane, place))
    out.triangle({vertex[a], vertex[b], vertex[c]}, {uv[a], uv[b], uv[c]});
}

}  // namespace candela
