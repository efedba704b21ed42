#include "accel/bounding_volume.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "geometry/polygon.h"
#include "geometry/sphere.h"
#include "geometry/triangle_mesh.h"

namespace candela {

BoundingSphere BoundingSphere::around(std::span<const Vec3> points) {
  BoundingSphere sphere;
  if (points.empty()) return sphere;
  Vec3 sum;
  for (const Vec3& p : points) sum += p;
  sphere.center = sum / static_cast<double>(points.size());
  double farthest = 0;
  for (const Vec3& p : points) farthest = std::max(farthest, length_squared(p - sphere.center));
  // A hair larger, so rounding never lets a surface point fall outside.
  sphere.radius = std::sqrt(farthest) * (1 + 1e-12);
  return sphere;
}

bool BoundingSphere::hit_by(const Ray& ray) const {
  // 000 §5.6.1's early exits: the closest approach, then the chord.
  const Vec3 to_center = center - ray.origin;
  const double mu = dot(ray.direction, to_center);
  const Vec3 perpendicular = to_center - ray.direction * mu;
  const double gamma = radius * radius - dot(perpendicular, perpendicular);
  if (gamma < 0) return false;
  const double half_chord = std::sqrt(gamma);
  return mu + half_chord > ray.t_min && mu - half_chord < ray.t_max;
}

const std::array<Vec3, 7> KayKajiyaSlabs::kNormals = [] {
  const double s = 1 / std::sqrt(3.0);
  return std::array<Vec3, 7>{Vec3{1, 0, 0},  Vec3{0, 1, 0},  Vec3{0, 0, 1}, Vec3{s, s, s},
                             Vec3{-s, s, s}, Vec3{s, -s, s}, Vec3{s, s, -s}};
}();

KayKajiyaSlabs KayKajiyaSlabs::around(std::span<const Vec3> points) {
  KayKajiyaSlabs slabs;
  slabs.lower.fill(kInfinity);
  slabs.upper.fill(-kInfinity);
  for (const Vec3& p : points)
    for (int i = 0; i < 7; ++i) {
      const double d = dot(kNormals[i], p);
      slabs.lower[i] = std::min(slabs.lower[i], d);
      slabs.upper[i] = std::max(slabs.upper[i], d);
    }
  // Outward by a relative hair against rounding.
  for (int i = 0; i < 7; ++i) {
    const double pad = 1e-12 * std::max({1.0, std::fabs(slabs.lower[i]), std::fabs(slabs.upper[i])});
    slabs.lower[i] -= pad;
    slabs.upper[i] += pad;
  }
  return slabs;
}

bool KayKajiyaSlabs::hit_by(const Ray& ray) const {
  // Kay & Kajiya 1986: each pair of planes n·p = lower, n·p = upper cuts the ray in an
  // interval; the ray meets the volume when the intervals overlap.
  double t_near = ray.t_min, t_far = ray.t_max;
  for (int i = 0; i < 7; ++i) {
    const double along = dot(kNormals[i], ray.direction);
    const double at_origin = dot(kNormals[i], ray.origin);
    if (along == 0) {
      if (at_origin < lower[i] || at_origin > upper[i]) return false;
      continue;
    }
    double t0 = (lower[i] - at_origin) / along, t1 = (upper[i] - at_origin) / along;
    if (t0 > t1) std::swap(t0, t1);
    t_near = std::max(t_near, t0);
    t_far = std::min(t_far, t1);
    if (t_near > t_far) return false;
  }
  return true;
}

void bounding_points(const Shape& shape, std::vector<Vec3>& points) {
  if (const auto* triangle = dynamic_cast<const MeshTriangle*>(&shape)) {
    const auto& corners = triangle->mesh().triangles[triangle->triangle_index()];
    for (const uint32_t corner : corners) points.push_back(triangle->mesh().positions[corner]);
    return;
  }
  if (const auto* polygon = dynamic_cast<const Polygon*>(&shape)) {
    const auto& vertices = polygon->vertices();
    points.insert(points.end(), vertices.begin(), vertices.end());
    return;
  }
  if (const auto* sphere = dynamic_cast<const Sphere*>(&shape)) {
    // The 6 poles and the 8 corners of the cube of half-edge r/√3·√3: together their hull holds
    // the sphere's extent along the 7 slab normals (the slab test is exact for these
    // directions); the bounding sphere of the 6 poles alone is the sphere itself.
    const double r = sphere->radius();
    const Vec3 c = sphere->center();
    for (int axis = 0; axis < 3; ++axis)
      for (const double sign : {-1.0, 1.0}) {
        Vec3 offset;
        offset[axis] = sign * r;
        points.push_back(c + offset);
      }
    for (int i = 3; i < 7; ++i) {
      points.push_back(c + KayKajiyaSlabs::kNormals[i] * r);
      points.push_back(c - KayKajiyaSlabs::kNormals[i] * r);
    }
    return;
  }
  const Bounds3 b = shape.bounds();
  for (int corner = 0; corner < 8; ++corner)
    points.push_back({(corner & 1) ? b.upper.x : b.lower.x, (corner & 2) ? b.upper.y : b.lower.y,
                      (corner & 4) ? b.upper.z : b.lower.z});
}

ObjectBound::ObjectBound(BoundingVolumeKind kind, std::span<const Primitive> primitives) : kind_(kind) {
  std::vector<Vec3> points;
  for (const Primitive& primitive : primitives) {
    if (!primitive.shape->bounds().is_finite()) {
      unbounded_ = true;
      return;
    }
    bounding_points(*primitive.shape, points);
  }
  switch (kind_) {
    case BoundingVolumeKind::none:
      break;
    case BoundingVolumeKind::sphere:
      sphere_ = BoundingSphere::around(points);
      break;
    case BoundingVolumeKind::box:
      for (const Primitive& primitive : primitives) box_.extend(primitive.shape->bounds());
      break;
    case BoundingVolumeKind::slabs:
      slabs_ = KayKajiyaSlabs::around(points);
      break;
  }
}

bool ObjectBound::hit_by(const Ray& ray) const {
  if (unbounded_) return true;
  switch (kind_) {
    case BoundingVolumeKind::none:
      return true;
    case BoundingVolumeKind::sphere:
      return sphere_.hit_by(ray);
    case BoundingVolumeKind::box: {
      double t_enter, t_exit;
      return box_.intersect(ray, t_enter, t_exit);
    }
    case BoundingVolumeKind::slabs:
      return slabs_.hit_by(ray);
  }
  return true;
}

}  // namespace candela
