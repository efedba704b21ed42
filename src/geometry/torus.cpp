#include "geometry/torus.h"

#include <cmath>
#include <stdexcept>

#include "geometry/tessellation.h"
#include "math/constants.h"
#include "math/direction.h"
#include "math/polynomial.h"

namespace candela {

Torus::Torus(const Vec3& center, const Vec3& axis, double major_radius, double minor_radius)
    : center_(center), major_radius_(major_radius), minor_radius_(minor_radius) {
  if (!is_finite(center)) throw std::invalid_argument("center must be finite");
  const std::optional<Vec3> unit = direction_of(axis);
  if (!unit) throw std::invalid_argument("axis must be non-zero");
  if (!(major_radius > 0) || !std::isfinite(major_radius))
    throw std::invalid_argument("major radius must be > 0");
  if (!(minor_radius > 0) || !std::isfinite(minor_radius))
    throw std::invalid_argument("minor radius must be > 0");
  axis_ = *unit;
  orthonormal_basis(axis_, x_axis_, y_axis_);
}

double Torus::implicit(const Vec3& p) const {
  const double major_squared = major_radius_ * major_radius_;
  const double sum = dot(p, p) + major_squared - minor_radius_ * minor_radius_;
  return sum * sum - 4 * major_squared * (p.x * p.x + p.y * p.y);
}

Vec3 Torus::gradient(const Vec3& p) const {
  const double major_squared = major_radius_ * major_radius_;
  const double sum = dot(p, p) + major_squared - minor_radius_ * minor_radius_;
  return Vec3{p.x * (sum - 2 * major_squared), p.y * (sum - 2 * major_squared), p.z * sum} * 4;
}

double Torus::nearest_t(const Ray& ray, Vec3& local) const {
  Vec3 o = to_local(ray.origin - center_);
  const Vec3 d = to_local(ray.direction);
  // The bounding sphere (as in Sphere::nearest_t, from the perpendicular offset).
  const double bound = major_radius_ + minor_radius_;
  const double mu = -dot(o, d);
  const Vec3 perpendicular = o + d * mu;
  const double gamma = bound * bound - dot(perpendicular, perpendicular);
  if (gamma <= 0) return kInfinity;
  const double root = std::sqrt(gamma);
  const double t_enter = mu - root, t_exit = mu + root;
  if (t_exit <= ray.t_min || t_enter >= ray.t_max) return kInfinity;
  // Move the origin to the entry point when it is outside: t = t0 + s.
  const double t0 = std::max(0.0, t_enter);
  o += d * t0;
  // |o + s d|^2 = s^2 + 2 k s + |o|^2 (|d| = 1); with g = |o|^2 + R^2 - r^2 the torus
  // function along the ray is (s^2 + 2 k s + g)^2 - 4 R^2 ((ox + s dx)^2 + (oy + s dy)^2).
  const double major_squared = major_radius_ * major_radius_;
  const double k = dot(o, d);
  const double g = dot(o, o) + major_squared - minor_radius_ * minor_radius_;
  const double four_major_squared = 4 * major_squared;
  double roots[4];
  const int count = solve_quartic(1, 4 * k, 4 * k * k + 2 * g - four_major_squared * (d.x * d.x + d.y * d.y),
                                  4 * k * g - 2 * four_major_squared * (o.x * d.x + o.y * d.y),
                                  g * g - four_major_squared * (o.x * o.x + o.y * o.y), roots);
  double best = kInfinity;
  for (int i = 0; i < count; ++i) {
    // Newton steps on the torus function itself, kept while they reduce it.
    double s = roots[i];
    double value = implicit(o + d * s);
    for (int step = 0; step < 3 && value != 0; ++step) {
      const double derivative = dot(gradient(o + d * s), d);
      if (derivative == 0) break;
      const double next = s - value / derivative;
      const double next_value = implicit(o + d * next);
      if (!(std::fabs(next_value) < std::fabs(value))) break;
      s = next;
      value = next_value;
    }
    const double t = t0 + s;
    if (t > ray.t_min && t < ray.t_max && t < best) {
      best = t;
      local = o + d * s;
    }
  }
  return best;
}

bool Torus::intersect(const Ray& ray, SurfaceHit& hit) const {
  Vec3 local;
  const double t = nearest_t(ray, local);
  if (t == kInfinity) return false;
  hit.t = t;
  hit.position = ray.at(t);
  hit.object_position = hit.position;
  const double rho = std::sqrt(local.x * local.x + local.y * local.y);
  double phi = std::atan2(local.y, local.x);
  if (phi < 0) phi += 2 * kPi;
  const double cos_phi = std::cos(phi), sin_phi = std::sin(phi);
  // The tube angle about the circle of centres, and the outward normal from that circle.
  double theta = std::atan2(local.z, rho - major_radius_);
  if (theta < 0) theta += 2 * kPi;
  const double cos_theta = std::cos(theta), sin_theta = std::sin(theta);
  const Vec3 radial = x_axis_ * cos_phi + y_axis_ * sin_phi;
  const Vec3 tangent = y_axis_ * cos_phi - x_axis_ * sin_phi;
  Vec3 normal = radial * cos_theta + axis_ * sin_theta;
  if (rho == 0) {
    // On the axis (a spindle torus): the gradient, or the axis where it vanishes.
    const Vec3 g = gradient(local);
    const Vec3 world = x_axis_ * g.x + y_axis_ * g.y + axis_ * g.z;
    normal = length_squared(world) > 0 ? normalize(world) : (local.z < 0 ? -axis_ : axis_);
  }
  hit.geometric_normal = normal;
  hit.shading_normal = normal;
  hit.uv = {phi / (2 * kPi), theta / (2 * kPi)};
  // p = (R + r cos θ)(cos φ, sin φ) + r sin θ axis.
  hit.dpdu = tangent * (2 * kPi * (major_radius_ + minor_radius_ * cos_theta));
  hit.dpdv = (axis_ * cos_theta - radial * sin_theta) * (2 * kPi * minor_radius_);
  return true;
}

bool Torus::occluded(const Ray& ray) const {
  Vec3 local;
  return nearest_t(ray, local) < kInfinity;
}

Bounds3 Torus::bounds() const {
  // Along world axis i the circle of centres reaches R sqrt(1 - axis_i^2), the tube r more.
  Vec3 extent;
  for (int i = 0; i < 3; ++i)
    extent[i] = major_radius_ * std::sqrt(std::max(0.0, 1.0 - axis_[i] * axis_[i])) + minor_radius_;
  return {center_ - extent, center_ + extent};
}

double Torus::area() const {
  if (minor_radius_ > major_radius_) return 0;
  return 4 * kPi * kPi * major_radius_ * minor_radius_;
}

bool Torus::sample_area(const Vec2& u, SurfaceSample& sample) const {
  const double R = major_radius_, r = minor_radius_;
  if (r > R) return false;
  // Solve R θ + r sin θ = 2π R u.y for θ in [0, 2π] (increasing since R + r cos θ >= 0).
  const double target = 2 * kPi * R * u.y;
  double low = 0, high = 2 * kPi;
  double theta = 2 * kPi * u.y;
  for (int iteration = 0; iteration < 64; ++iteration) {
    const double value = R * theta + r * std::sin(theta) - target;
    if (value == 0) break;
    if (value < 0)
      low = theta;
    else
      high = theta;
    const double derivative = R + r * std::cos(theta);
    double next = derivative > 0 ? theta - value / derivative : 0.5 * (low + high);
    if (!(next > low && next < high)) next = 0.5 * (low + high);
    if (std::fabs(next - theta) <= 1e-15 * 2 * kPi) {
      theta = next;
      break;
    }
    theta = next;
  }
  const double phi = 2 * kPi * u.x;
  const double cos_theta = std::cos(theta), sin_theta = std::sin(theta);
  const Vec3 radial = x_axis_ * std::cos(phi) + y_axis_ * std::sin(phi);
  sample.position = center_ + radial * (R + r * cos_theta) + axis_ * (r * sin_theta);
  sample.normal = normalize(radial * cos_theta + axis_ * sin_theta);
  sample.pdf = 1 / area();
  return true;
}

double Torus::pdf_area(const SurfaceHit&) const {
  const double a = area();
  return a > 0 ? 1 / a : 0;
}

void Torus::tessellate(const TessellationSettings& settings, TriangleMesh& mesh) const {
  MeshAppender out(mesh);
  const int ring_divisions = turn_divisions(settings);
  const int tube_divisions = std::max(3, ring_divisions / 2);
  const std::vector<Vec2> ring_circle = unit_circle(ring_divisions);
  const std::vector<Vec2> tube_circle = unit_circle(tube_divisions);
  // Ring j at tube angle θ = 2π j / tube_divisions: p = (R + r cos θ) radial(φ) + r sin θ axis.
  // Area-true (tessellation.h): the tube's points moved out from its centre line by one factor.
  const auto build = [&](double scale, MeshAppender& to) {
    const double minor = minor_radius_ * scale;
    std::vector<std::vector<Vec3>> rings;
    for (const Vec2& tube : tube_circle)
      rings.push_back(circle_points(center_ + axis_ * (minor * tube.y), x_axis_, y_axis_,
                                    major_radius_ + minor * tube.x, ring_circle));
    append_revolution_grid(rings, /*wrap_rings=*/true, to);
  };
  build(area_true_scale(settings, area(), build), out);
}

}  // namespace candela
