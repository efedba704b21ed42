#include "geometry/plane.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "geometry/flat_surface.h"
#include "geometry/tessellation.h"
#include "math/constants.h"
#include "math/direction.h"

namespace candela {

Plane::Plane(const Vec3& point, const Vec3& normal) : point_(point) {
  if (!is_finite(point)) throw std::invalid_argument("point must be finite");
  const std::optional<Vec3> unit = direction_of(normal);
  if (!unit) throw std::invalid_argument("normal must be non-zero");
  normal_ = *unit;
  orthonormal_basis(normal_, u_axis_, v_axis_);
}

double Plane::nearest_t(const Ray& ray) const {
  return plane_hit_distance(ray, point_, normal_);
}

bool Plane::intersect(const Ray& ray, SurfaceHit& hit) const {
  const double t = nearest_t(ray);
  if (t == kInfinity) return false;
  fill_flat_hit(ray, t, normal_, hit);
  const Vec3 local = hit.position - point_;
  hit.uv = {dot(local, u_axis_), dot(local, v_axis_)};
  hit.dpdu = u_axis_;
  hit.dpdv = v_axis_;
  return true;
}

bool Plane::occluded(const Ray& ray) const {
  return nearest_t(ray) < kInfinity;
}

bool Plane::hit_distance(const Ray& ray, double& t) const {
  t = nearest_t(ray);
  return t < kInfinity;
}

Bounds3 Plane::bounds() const {
  return {Vec3{-kInfinity, -kInfinity, -kInfinity}, Vec3{kInfinity, kInfinity, kInfinity}};
}

void Plane::tessellate(const TessellationSettings& settings, TriangleMesh& mesh) const {
  MeshAppender out(mesh);
  const Bounds3& box = settings.clip;
  if (box.empty() || !box.is_finite()) return;
  // The box's corners: bit k of the index picks the upper bound on axis k.
  std::array<Vec3, 8> corners;
  std::array<double, 8> distance;  // signed, along the normal
  for (int i = 0; i < 8; ++i) {
    for (int axis = 0; axis < 3; ++axis)
      corners[i][axis] = ((i >> axis) & 1) ? box.upper[axis] : box.lower[axis];
    distance[i] = dot(normal_, corners[i] - point_);
  }
  // The plane meets the box in a convex polygon whose vertices are the corners on the plane
  // and the points where the plane crosses an edge between corners on opposite sides.
  std::vector<Vec3> points;
  for (int i = 0; i < 8; ++i) {
    if (distance[i] == 0) points.push_back(corners[i]);
  }
  for (int i = 0; i < 8; ++i) {
    for (int axis = 0; axis < 3; ++axis) {
      const int j = i | (1 << axis);
      if (j == i) continue;  // each edge once, from its lower corner
      if (!((distance[i] < 0 && distance[j] > 0) || (distance[i] > 0 && distance[j] < 0))) continue;
      if (normal_[axis] == 0) continue;  // parallel to the plane (the distances are then equal)
      // The edge's other two coordinates are exact; the third is solved from the plane
      // equation normal · (p - point) = 0 (more accurate on the plane than interpolating the
      // distances), then kept on the edge.
      Vec3 crossing = corners[i];
      double rest = 0;
      for (int other = 0; other < 3; ++other) {
        if (other != axis) rest += normal_[other] * (crossing[other] - point_[other]);
      }
      crossing[axis] = std::clamp(point_[axis] - rest / normal_[axis], box.lower[axis], box.upper[axis]);
      points.push_back(crossing);
    }
  }
  // A corner reached along several edges (clamped onto it) appears more than once.
  const auto lexicographic = [](const Vec3& a, const Vec3& b) {
    return std::array<double, 3>{a.x, a.y, a.z} < std::array<double, 3>{b.x, b.y, b.z};
  };
  std::sort(points.begin(), points.end(), lexicographic);
  points.erase(std::unique(points.begin(), points.end()), points.end());
  if (points.size() < 3) return;
  // Counter-clockwise about the normal: by angle in the (u_axis_, v_axis_) frame about the
  // points' mean, which lies inside a convex polygon.
  Vec3 mean;
  for (const Vec3& p : points) mean += p;
  mean = mean / static_cast<double>(points.size());
  const auto angle = [&](const Vec3& p) {
    return std::atan2(dot(p - mean, v_axis_), dot(p - mean, u_axis_));
  };
  std::sort(points.begin(), points.end(), [&](const Vec3& a, const Vec3& b) { return angle(a) < angle(b); });
  std::vector<uint32_t> ids;
  std::vector<Vec2> uvs;
  for (const Vec3& p : points) {
    ids.push_back(out.vertex(p));
    uvs.push_back({dot(p - point_, u_axis_), dot(p - point_, v_axis_)});  // as intersect reports
  }
  for (std::size_t k = 1; k + 1 < points.size(); ++k)
    out.triangle({ids[0], ids[k], ids[k + 1]}, {uvs[0], uvs[k], uvs[k + 1]});
}

}  // namespace candela
