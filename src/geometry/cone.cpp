#include "geometry/cone.h"

#include <cmath>
#include <stdexcept>

#include "geometry/disc.h"
#include "math/constants.h"

namespace candela {

Cone::Cone(const Vec3& base, double base_radius, const Vec3& cap, double cap_radius, bool capped)
    : base_(base), base_radius_(base_radius), cap_(cap), cap_radius_(cap_radius), capped_(capped) {
  if (!is_finite(base) || !is_finite(cap)) throw std::invalid_argument("end points must be finite");
  if (!(base_radius >= 0) || !(cap_radius >= 0) || !std::isfinite(base_radius) ||
      !std::isfinite(cap_radius))
    throw std::invalid_argument("radii must be >= 0");
  if (base_radius == 0 && cap_radius == 0) throw std::invalid_argument("radii must not both be 0");
  height_ = length(cap - base);
  if (!(height_ > 0) || !std::isfinite(height_))
    throw std::invalid_argument("base and cap must differ");
  slope_ = (cap_radius - base_radius) / height_;
  axis_ = (cap - base) / height_;
  orthonormal_basis(axis_, x_axis_, y_axis_);
}

double Cone::nearest_t(const Ray& ray, Part& part) const {
  const Vec3 o = to_local(ray.origin - base_);
  const Vec3 d = to_local(ray.direction);
  double best = kInfinity;
  const auto consider = [&](double t, Part candidate) {
    if (t > ray.t_min && t < ray.t_max && t < best) {
      best = t;
      part = candidate;
    }
  };
  // Side: (ox + t dx)^2 + (oy + t dy)^2 - (r0 + k (oz + t dz))^2 = a t^2 + 2 b t + c = 0.
  const double radius_at_origin = base_radius_ + slope_ * o.z;
  const double radius_rate = slope_ * d.z;
  const double a = d.x * d.x + d.y * d.y - radius_rate * radius_rate;
  const double b = o.x * d.x + o.y * d.y - radius_at_origin * radius_rate;
  const double c = o.x * o.x + o.y * o.y - radius_at_origin * radius_at_origin;
  const double discriminant = b * b - a * c;
  if (discriminant >= 0) {
    // Without cancellation: q = -(b + sign(b) sqrt(disc)), roots q / a and c / q. When a = 0
    // (a ray parallel to a generator) q / a is infinite and c / q = -c / 2b is the only root.
    const double q = -(b + std::copysign(std::sqrt(discriminant), b));
    if (q != 0) {
      for (const double t : {q / a, c / q}) {
        if (!std::isfinite(t)) continue;
        const double z = o.z + d.z * t;
        if (z >= 0 && z <= height_) consider(t, Part::kSide);
      }
    }
  }
  if (capped_ && d.z != 0) {
    if (base_radius_ > 0) {
      const double t_base = -o.z / d.z;
      const double x = o.x + d.x * t_base, y = o.y + d.y * t_base;
      if (x * x + y * y <= base_radius_ * base_radius_) consider(t_base, Part::kBaseCap);
    }
    if (cap_radius_ > 0) {
      const double t_top = (height_ - o.z) / d.z;
      const double x = o.x + d.x * t_top, y = o.y + d.y * t_top;
      if (x * x + y * y <= cap_radius_ * cap_radius_) consider(t_top, Part::kTopCap);
    }
  }
  return best;
}

bool Cone::intersect(const Ray& ray, SurfaceHit& hit) const {
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
  const double cos_phi = std::cos(phi), sin_phi = std::sin(phi);
  const Vec3 radial = x_axis_ * cos_phi + y_axis_ * sin_phi;
  const Vec3 tangent = y_axis_ * cos_phi - x_axis_ * sin_phi;
  if (part == Part::kSide) {
    const double z = std::clamp(local.z, 0.0, height_);
    const double side_radius = std::max(0.0, base_radius_ + slope_ * z);
    if (r > 0) {
      hit.geometric_normal = normalize(radial - axis_ * slope_);
    } else {
      hit.geometric_normal = slope_ < 0 ? axis_ : -axis_;  // the apex
    }
    hit.uv = {phi / (2 * kPi), z / height_};
    hit.dpdu = tangent * (2 * kPi * side_radius);
    hit.dpdv = (radial * slope_ + axis_) * height_;
  } else {
    const bool top = part == Part::kTopCap;
    fill_cap_hit(top, axis_, radial, tangent, phi, r, top ? cap_radius_ : base_radius_, hit);
  }
  hit.shading_normal = hit.geometric_normal;
  return true;
}

bool Cone::occluded(const Ray& ray) const {
  Part part = Part::kSide;
  return nearest_t(ray, part) < kInfinity;
}

Bounds3 Cone::bounds() const {
  // The cone is the convex hull of its two end discs.
  Bounds3 bounds = disc_bounds(base_, axis_, base_radius_);
  bounds.extend(disc_bounds(cap_, axis_, cap_radius_));
  return bounds;
}

}  // namespace candela
