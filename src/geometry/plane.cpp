#include "geometry/plane.h"

#include <cmath>
#include <stdexcept>

#include "geometry/flat_surface.h"
#include "math/constants.h"

namespace candela {

Plane::Plane(const Vec3& point, const Vec3& normal) : point_(point) {
  if (!is_finite(point)) throw std::invalid_argument("point must be finite");
  const double normal_length = length(normal);
  if (!(normal_length > 0) || !std::isfinite(normal_length))
    throw std::invalid_argument("normal must be non-zero");
  normal_ = normal / normal_length;
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

bool Plane::occluded(const Ray& ray) const { return nearest_t(ray) < kInfinity; }

Bounds3 Plane::bounds() const {
  return {Vec3{-kInfinity, -kInfinity, -kInfinity}, Vec3{kInfinity, kInfinity, kInfinity}};
}

}  // namespace candela
