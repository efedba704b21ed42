#include "geometry/polygon.h"

#include <cmath>
#include <stdexcept>

#include "geometry/flat_surface.h"
#include "math/constants.h"

namespace candela {

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

bool Polygon::occluded(const Ray& ray) const { return nearest_t(ray) < kInfinity; }

Bounds3 Polygon::bounds() const { return bounds_; }

}  // namespace candela
