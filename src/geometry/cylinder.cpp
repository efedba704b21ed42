#include "geometry/cylinder.h"

#include <cmath>
#include <stdexcept>

#include "geometry/disc.h"
#include "math/constants.h"

namespace candela {

Cylinder::Cylinder(const Vec3& base, const Vec3& cap, double radius, bool capped)
    : base_(base), cap_(cap), radius_(radius), capped_(capped) {
  if (!is_finite(base) || !is_finite(cap)) throw std::invalid_argument("end points must be finite");
  if (!(radius > 0) || !std::isfinite(radius)) throw std::invalid_argument("radius must be > 0");
  height_ = length(cap - base);
  if (!(height_ > 0) || !std::isfinite(height_))
    throw std::invalid_argument("base and cap must differ");
  axis_ = (cap - base) / height_;
  orthonormal_basis(axis_, x_axis_, y_axis_);
}

double Cylinder::nearest_t(const Ray& ray, Part& part) const {
  const Vec3 o = to_local(ray.origin - base_);
  const Vec3 d = to_local(ray.direction);
  double best = kInfinity;
  const auto consider = [&](double t, Part candidate) {
    if (t > ray.t_min && t < ray.t_max && t < best) {
      best = t;
      part = candidate;
    }
  };
  // Side: (ox + t dx)^2 + (oy + t dy)^2 = r^2. As for the sphere, gamma = r^2 - (distance of
  // the closest approach in the xy plane)^2 is formed from the perpendicular offset.
  const double a = d.x * d.x + d.y * d.y;
  if (a > 0) {
    const double t_closest = -(o.x * d.x + o.y * d.y) / a;
    const double px = o.x + d.x * t_closest, py = o.y + d.y * t_closest;
    const double gamma = radius_ * radius_ - (px * px + py * py);
    if (gamma > 0) {  // a tangent ray does not count
      const double root = std::sqrt(gamma / a);
      for (const double t : {t_closest - root, t_closest + root}) {
        const double z = o.z + d.z * t;
        if (z >= 0 && z <= height_) consider(t, Part::kSide);
      }
    }
  }
  if (capped_ && d.z != 0) {
    const double radius_squared = radius_ * radius_;
    const double t_base = -o.z / d.z;
    const double bx = o.x + d.x * t_base, by = o.y + d.y * t_base;
    if (bx * bx + by * by <= radius_squared) consider(t_base, Part::kBaseCap);
    const double t_top = (height_ - o.z) / d.z;
    const double tx = o.x + d.x * t_top, ty = o.y + d.y * t_top;
    if (tx * tx + ty * ty <= radius_squared) consider(t_top, Part::kTopCap);
  }
  return best;
}

bool Cylinder::intersect(const Ray& ray, SurfaceHit& hit) const {
  Part part = Part::kSide;
  const double t = nearest_t(ray, part);
  if (t == kInfinity) return false;
  hit.t = t;
  hit.position = ray.at(t);
  hit.object_position = hit.position;
  const Vec3 local = to_local(hit.position - base_);
  const double r = std::sqrt(local.x * local.x + local.y * local.y);
  double phi = std::atan2(local.y, local.x);
  if (phi < 0) phi += 2 * kPi;
  // The unit radial and tangential (counter-clockwise about +axis) directions.
  const double cos_phi = std::cos(phi), sin_phi = std::sin(phi);
  const Vec3 radial = x_axis_ * cos_phi + y_axis_ * sin_phi;
  const Vec3 tangent = y_axis_ * cos_phi - x_axis_ * sin_phi;
  if (part == Part::kSide) {
    hit.geometric_normal = radial;
    hit.uv = {phi / (2 * kPi), std::clamp(local.z / height_, 0.0, 1.0)};
    hit.dpdu = tangent * (2 * kPi * radius_);
    hit.dpdv = axis_ * height_;
  } else {
    fill_cap_hit(part == Part::kTopCap, axis_, radial, tangent, phi, r, radius_, hit);
  }
  hit.shading_normal = hit.geometric_normal;
  return true;
}

bool Cylinder::occluded(const Ray& ray) const {
  Part part = Part::kSide;
  return nearest_t(ray, part) < kInfinity;
}

Bounds3 Cylinder::bounds() const {
  Bounds3 bounds = disc_bounds(base_, axis_, radius_);
  bounds.extend(disc_bounds(cap_, axis_, radius_));
  return bounds;
}

}  // namespace candela
