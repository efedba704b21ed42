#include "geometry/disc.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "geometry/flat_surface.h"
#include "geometry/surface_sampling.h"
#include "geometry/tessellation.h"
#include "math/constants.h"
#include "math/direction.h"
#include "sampling/warps.h"

namespace candela {

Disc::Disc(const Vec3& center, const Vec3& normal, double radius, double inner_radius)
    : center_(center), radius_(radius), inner_radius_(inner_radius) {
  if (!is_finite(center)) throw std::invalid_argument("center must be finite");
  const std::optional<Vec3> unit = direction_of(normal);
  if (!unit) throw std::invalid_argument("normal must be non-zero");
  if (!(radius > 0) || !std::isfinite(radius)) throw std::invalid_argument("radius must be > 0");
  if (!(inner_radius >= 0) || !(inner_radius < radius))
    throw std::invalid_argument("inner_radius must be >= 0 and < radius");
  normal_ = *unit;
  orthonormal_basis(normal_, u_axis_, v_axis_);
}

double Disc::nearest_t(const Ray& ray) const {
  // The plane of the disc (000 eq. 5-13), then the distance from the centre.
  const double t = plane_hit_distance(ray, center_, normal_);
  if (t == kInfinity) return kInfinity;
  const Vec3 offset = ray.at(t) - center_;
  const double x = dot(offset, u_axis_), y = dot(offset, v_axis_);
  const double r_squared = x * x + y * y;
  if (r_squared > radius_ * radius_ || r_squared < inner_radius_ * inner_radius_) return kInfinity;
  return t;
}

bool Disc::intersect(const Ray& ray, SurfaceHit& hit) const {
  const double t = nearest_t(ray);
  if (t == kInfinity) return false;
  fill_flat_hit(ray, t, normal_, hit);
  const Vec3 offset = hit.position - center_;
  const double x = dot(offset, u_axis_), y = dot(offset, v_axis_);
  const double r = std::sqrt(x * x + y * y);
  double phi = std::atan2(y, x);
  if (phi < 0) phi += 2 * kPi;
  const double width = radius_ - inner_radius_;
  hit.uv = {phi / (2 * kPi), std::clamp((radius_ - r) / width, 0.0, 1.0)};
  // dp/du = 2π (-y, x); dp/dv = -(radius - inner) (x, y) / r, the inward radial direction
  // (taken along the first axis at the centre).
  hit.dpdu = (v_axis_ * x - u_axis_ * y) * (2 * kPi);
  const Vec3 outward = r > 0 ? (u_axis_ * x + v_axis_ * y) / r : u_axis_;
  hit.dpdv = outward * -width;
  return true;
}

bool Disc::occluded(const Ray& ray) const {
  return nearest_t(ray) < kInfinity;
}

Bounds3 Disc::bounds() const {
  return disc_bounds(center_, normal_, radius_);
}

void Disc::tessellate(const TessellationSettings& settings, TriangleMesh& mesh) const {
  MeshAppender out(mesh);
  const std::vector<Vec2> circle = unit_circle(turn_divisions(settings));
  // v = 0 on the rim, 1 on the inner rim; u counter-clockwise about the normal from u_axis_.
  // Area-true (tessellation.h): both rims moved out from the centre by one factor.
  const auto build = [&](double scale, MeshAppender& to) {
    append_revolution_grid({circle_points(center_, u_axis_, v_axis_, radius_ * scale, circle),
                            circle_points(center_, u_axis_, v_axis_, inner_radius_ * scale, circle)},
                           /*wrap_rings=*/false, to);
  };
  build(area_true_scale(settings, area(), build), out);
}

double Disc::area() const {
  return kPi * (radius_ * radius_ - inner_radius_ * inner_radius_);
}

bool Disc::sample_area(const Vec2& u, SurfaceSample& sample) const {
  const Vec2 unit = square_to_uniform_disc_concentric(u);
  double x = unit.x * radius_, y = unit.y * radius_;
  if (inner_radius_ > 0) {
    const double rho_squared = unit.x * unit.x + unit.y * unit.y;
    const double rho = std::sqrt(rho_squared);
    const double r = std::sqrt(inner_radius_ * inner_radius_ +
                               rho_squared * (radius_ * radius_ - inner_radius_ * inner_radius_));
    const double scale = rho > 0 ? r / rho : 0;
    x = rho > 0 ? unit.x * scale : inner_radius_;
    y = unit.y * scale;
  }
  sample.position = center_ + u_axis_ * x + v_axis_ * y;
  sample.normal = normal_;
  sample.pdf = 1 / area();
  return true;
}

double Disc::pdf_area(const SurfaceHit&) const {
  return 1 / area();
}

void fill_cap_hit(bool top, const Vec3& axis, const Vec3& radial, const Vec3& tangent, double phi, double r,
                  double cap_radius, SurfaceHit& hit) {
  hit.geometric_normal = top ? axis : -axis;
  // Seen from outside the base cap, counter-clockwise is clockwise about +axis.
  hit.uv = {top ? phi / (2 * kPi) : 1.0 - phi / (2 * kPi), std::clamp(1.0 - r / cap_radius, 0.0, 1.0)};
  hit.dpdu = tangent * ((top ? 2 : -2) * kPi * r);
  hit.dpdv = radial * -cap_radius;
}

Bounds3 disc_bounds(const Vec3& center, const Vec3& unit_normal, double radius) {
  Vec3 extent;
  for (int axis = 0; axis < 3; ++axis)
    extent[axis] = radius * std::sqrt(std::max(0.0, 1.0 - unit_normal[axis] * unit_normal[axis]));
  return {center - extent, center + extent};
}

}  // namespace candela
