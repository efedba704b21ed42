#include "geometry/cone.h"

#include <cmath>
#include <stdexcept>

#include "geometry/disc.h"
#include "geometry/surface_sampling.h"
#include "geometry/tessellation.h"
#include "math/constants.h"

namespace candela {

Cone::Cone(const Vec3& base, double base_radius, const Vec3& cap, double cap_radius, bool capped)
    : frame_(base, cap), base_radius_(base_radius), cap_(cap), cap_radius_(cap_radius), capped_(capped) {
  if (!(base_radius >= 0) || !(cap_radius >= 0) || !std::isfinite(base_radius) || !std::isfinite(cap_radius))
    throw std::invalid_argument("radii must be >= 0");
  if (base_radius == 0 && cap_radius == 0) throw std::invalid_argument("radii must not both be 0");
  slope_ = (cap_radius - base_radius) / frame_.height();
}

double Cone::nearest_t(const Ray& ray, Part& part) const {
  Vec3 o, d;
  frame_.localize(ray, o, d);
  const double height = frame_.height();
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
        if (z >= 0 && z <= height) consider(t, Part::kSide);
      }
    }
  }
  if (capped_) {
    double t;
    if (base_radius_ > 0 && AxialFrame::cap_distance(o, d, 0, base_radius_, t)) consider(t, Part::kBaseCap);
    if (cap_radius_ > 0 && AxialFrame::cap_distance(o, d, height, cap_radius_, t)) consider(t, Part::kTopCap);
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
  const AxialFrame::Around at = frame_.around(hit.position);
  const Vec3& axis = frame_.axis();
  if (part == Part::kSide) {
    const double z = std::clamp(at.local.z, 0.0, frame_.height());
    const double side_radius = std::max(0.0, base_radius_ + slope_ * z);
    if (at.r > 0) {
      hit.geometric_normal = normalize(at.radial - axis * slope_);
    } else {
      hit.geometric_normal = slope_ < 0 ? axis : -axis;  // the apex
    }
    hit.uv = {at.phi / (2 * kPi), z / frame_.height()};
    hit.dpdu = at.tangent * (2 * kPi * side_radius);
    hit.dpdv = (at.radial * slope_ + axis) * frame_.height();
  } else {
    const bool top = part == Part::kTopCap;
    fill_cap_hit(top, axis, at.radial, at.tangent, at.phi, at.r, top ? cap_radius_ : base_radius_, hit);
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
  Bounds3 bounds = disc_bounds(frame_.base(), frame_.axis(), base_radius_);
  bounds.extend(disc_bounds(cap_, frame_.axis(), cap_radius_));
  return bounds;
}

double Cone::area() const {
  const double r0 = base_radius_, r1 = cap_radius_;
  const double side = kPi * (r0 + r1) * std::hypot(frame_.height(), r1 - r0);
  return capped_ ? side + kPi * (r0 * r0 + r1 * r1) : side;
}

bool Cone::sample_area(const Vec2& u, SurfaceSample& sample) const {
  const double r0 = base_radius_, r1 = cap_radius_, height = frame_.height();
  const double part_areas[3] = {kPi * (r0 + r1) * std::hypot(height, r1 - r0), capped_ ? kPi * r0 * r0 : 0,
                                capped_ ? kPi * r1 * r1 : 0};
  double choice = u.x;
  const int part = pick_by_area(part_areas, choice);
  if (part == 3) return false;
  const Vec3& axis = frame_.axis();
  if (part == 0) {
    // The side's area below height z is proportional to r(z)² − r0², so r = sqrt(r0² + u (r1² −
    // r0²)); then z = h (r − r0)/(r1 − r0) = h u (r0 + r1)/(r + r0), which needs no r1 ≠ r0.
    const double r = std::sqrt(r0 * r0 + choice * (r1 * r1 - r0 * r0));
    const double z = r + r0 > 0 ? std::min(height, height * choice * (r0 + r1) / (r + r0)) : 0;
    const double side_radius = std::max(0.0, r0 + slope_ * z);
    const Vec3 radial = frame_.radial(2 * kPi * u.y);
    sample.position = frame_.base() + axis * z + radial * side_radius;
    sample.normal = side_radius > 0 ? normalize(radial - axis * slope_) : (slope_ < 0 ? axis : -axis);
  } else {
    const bool top = part == 2;
    frame_.sample_end_disc(top ? cap_ : frame_.base(), top, top ? r1 : r0, {choice, u.y}, sample);
  }
  sample.pdf = 1 / area();
  return true;
}

double Cone::pdf_area(const SurfaceHit&) const {
  return 1 / area();
}

void Cone::tessellate(const TessellationSettings& settings, TriangleMesh& mesh) const {
  MeshAppender out(mesh);
  const std::vector<Vec2> circle = unit_circle(turn_divisions(settings));
  // Area-true (tessellation.h): the rims moved out from the axis by one factor.
  const auto build = [&](double scale, MeshAppender& to) {
    append_truncated_cone(frame_.base(), frame_.axis(), frame_.height(), frame_.x_axis(), frame_.y_axis(),
                          base_radius_ * scale, cap_radius_ * scale, capped_, circle, to);
  };
  build(area_true_scale(settings, area(), build), out);
}

}  // namespace candela
