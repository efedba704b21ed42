#include "geometry/cylinder.h"

#include <cmath>
#include <stdexcept>

#include "geometry/disc.h"
#include "geometry/surface_sampling.h"
#include "geometry/tessellation.h"
#include "math/constants.h"

namespace candela {

Cylinder::Cylinder(const Vec3& base, const Vec3& cap, double radius, bool capped)
    : frame_(base, cap), cap_(cap), radius_(radius), capped_(capped) {
  if (!(radius > 0) || !std::isfinite(radius)) throw std::invalid_argument("radius must be > 0");
}

double Cylinder::nearest_t(const Ray& ray, Part& part) const {
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
        if (z >= 0 && z <= height) consider(t, Part::kSide);
      }
    }
  }
  if (capped_) {
    double t;
    if (AxialFrame::cap_distance(o, d, 0, radius_, t)) consider(t, Part::kBaseCap);
    if (AxialFrame::cap_distance(o, d, height, radius_, t)) consider(t, Part::kTopCap);
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
  const AxialFrame::Around at = frame_.around(hit.position);
  if (part == Part::kSide) {
    hit.geometric_normal = at.radial;
    hit.uv = {at.phi / (2 * kPi), std::clamp(at.local.z / frame_.height(), 0.0, 1.0)};
    hit.dpdu = at.tangent * (2 * kPi * radius_);
    hit.dpdv = frame_.axis() * frame_.height();
  } else {
    fill_cap_hit(part == Part::kTopCap, frame_.axis(), at.radial, at.tangent, at.phi, at.r, radius_, hit);
  }
  hit.shading_normal = hit.geometric_normal;
  return true;
}

bool Cylinder::occluded(const Ray& ray) const {
  Part part = Part::kSide;
  return nearest_t(ray, part) < kInfinity;
}

Bounds3 Cylinder::bounds() const {
  Bounds3 bounds = disc_bounds(frame_.base(), frame_.axis(), radius_);
  bounds.extend(disc_bounds(cap_, frame_.axis(), radius_));
  return bounds;
}

double Cylinder::area() const {
  const double side = 2 * kPi * radius_ * frame_.height();
  return capped_ ? side + 2 * kPi * radius_ * radius_ : side;
}

bool Cylinder::sample_area(const Vec2& u, SurfaceSample& sample) const {
  const double cap_area = capped_ ? kPi * radius_ * radius_ : 0;
  const double part_areas[3] = {2 * kPi * radius_ * frame_.height(), cap_area, cap_area};
  double choice = u.x;
  const int part = pick_by_area(part_areas, choice);
  if (part == 3) return false;
  if (part == 0) {
    const Vec3 radial = frame_.radial(2 * kPi * u.y);
    sample.position = frame_.base() + frame_.axis() * (choice * frame_.height()) + radial * radius_;
    sample.normal = radial;
  } else {
    const bool top = part == 2;
    frame_.sample_end_disc(top ? cap_ : frame_.base(), top, radius_, {choice, u.y}, sample);
  }
  sample.pdf = 1 / area();
  return true;
}

double Cylinder::pdf_area(const SurfaceHit&) const {
  return 1 / area();
}

void Cylinder::tessellate(const TessellationSettings& settings, TriangleMesh& mesh) const {
  MeshAppender out(mesh);
  const std::vector<Vec2> circle = unit_circle(turn_divisions(settings));
  // Area-true (tessellation.h): the rims moved out from the axis by one factor.
  const auto build = [&](double scale, MeshAppender& to) {
    append_truncated_cone(frame_.base(), frame_.axis(), frame_.height(), frame_.x_axis(), frame_.y_axis(),
                          radius_ * scale, radius_ * scale, capped_, circle, to);
  };
  build(area_true_scale(settings, area(), build), out);
}

}  // namespace candela
