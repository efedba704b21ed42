#include "geometry/sphere.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "geometry/tessellation.h"
#include "math/constants.h"

namespace candela {

Sphere::Sphere(const Vec3& center, double radius) : center_(center), radius_(radius) {
  if (!(radius > 0) || !std::isfinite(radius)) throw std::invalid_argument("radius must be > 0");
}

double Sphere::nearest_t(const Ray& ray) const {
  // 000 eq. 5-10: T = C - O, mu = D.T, lambda = T.T.
  const Vec3 to_center = center_ - ray.origin;
  const double lambda = dot(to_center, to_center);
  const double radius_squared = radius_ * radius_;
  const bool origin_outside = lambda > radius_squared;
  const double mu = dot(ray.direction, to_center);
  // 000 Figure 38a: closest approach behind an outside origin, no hit.
  if (origin_outside && mu <= 0) return -1;
  // 000 eq. 5-11: gamma = mu^2 - lambda + R^2; a tangent ray does not count.
  // The difference is formed from the perpendicular distance for accuracy far away.
  const Vec3 perpendicular = to_center - ray.direction * mu;
  const double gamma = radius_squared - dot(perpendicular, perpendicular);
  if (gamma <= 0) return -1;
  const double root = std::sqrt(gamma);
  // Outside: t = mu - sqrt(gamma); on or inside: t = mu + sqrt(gamma). With t_min the near
  // root may be rejected and the far one accepted (the ray leaves through the far side).
  const double t_near = mu - root;
  const double t_far = mu + root;
  if (t_near > ray.t_min && t_near < ray.t_max) return t_near;
  if (t_far > ray.t_min && t_far < ray.t_max) return t_far;
  return -1;
}

bool Sphere::intersect(const Ray& ray, SurfaceHit& hit) const {
  const double t = nearest_t(ray);
  if (t < 0) return false;
  hit.t = t;
  hit.position = ray.at(t);
  const Vec3 local = (hit.position - center_) / radius_;
  hit.geometric_normal = normalize(local);
  hit.shading_normal = hit.geometric_normal;
  hit.object_position = hit.position;
  double phi = std::atan2(local.y, local.x);
  if (phi < 0) phi += 2 * kPi;
  const double theta = std::acos(std::clamp(local.z, -1.0, 1.0));
  hit.uv = {phi / (2 * kPi), 1.0 - theta / kPi};
  // dp/du = 2π r (-y, x, 0); dp/dv = -π r (z cos φ, z sin φ, -sin θ), so dpdu × dpdv is outward.
  hit.dpdu = Vec3{-local.y, local.x, 0} * (2 * kPi * radius_);
  hit.dpdv = Vec3{local.z * std::cos(phi), local.z * std::sin(phi), -std::sin(theta)} * (-kPi * radius_);
  return true;
}

bool Sphere::occluded(const Ray& ray) const {
  return nearest_t(ray) >= 0;
}

Bounds3 Sphere::bounds() const {
  const Vec3 extent{radius_, radius_, radius_};
  return {center_ - extent, center_ + extent};
}

void Sphere::tessellate(const TessellationSettings& settings, TriangleMesh& mesh) const {
  MeshAppender out(mesh);
  const int longitudes = turn_divisions(settings);
  const int bands = std::max(2, longitudes / 2);
  const std::vector<Vec2> circle = unit_circle(longitudes);
  // Ring j at v = j / bands, i.e. polar angle θ = π (1 - v), from the -z pole up; the poles
  // are set exactly (sin π is not 0 in floating point), so they collapse to single vertices.
  // Area-true (tessellation.h): every point moved out from the centre by one factor.
  const auto build = [&](double scale, MeshAppender& to) {
    const double radius = radius_ * scale;
    std::vector<std::vector<Vec3>> rings(bands + 1);
    for (int j = 0; j <= bands; ++j) {
      const double theta = kPi * (1.0 - static_cast<double>(j) / bands);
      const double cos_theta = j == 0 ? -1.0 : (j == bands ? 1.0 : std::cos(theta));
      const double sin_theta = (j == 0 || j == bands) ? 0.0 : std::sin(theta);
      rings[j] = circle_points(center_ + Vec3{0, 0, radius * cos_theta}, {1, 0, 0}, {0, 1, 0},
                               radius * sin_theta, circle);
    }
    append_revolution_grid(rings, /*wrap_rings=*/false, to);
  };
  build(area_true_scale(settings, area(), build), out);
}

}  // namespace candela

namespace candela {

double Sphere::area() const {
  return 4 * kPi * radius_ * radius_;
}

bool Sphere::sample_area(const Vec2& u, SurfaceSample& sample) const {
  // z = 1 − 2 u.x, so 1 − z² = 4 u.x (1 − u.x) without cancellation at the poles.
  const double z = 1 - 2 * u.x;
  const double r = 2 * std::sqrt(std::max(0.0, u.x * (1 - u.x)));
  const double phi = 2 * kPi * u.y;
  const Vec3 n{r * std::cos(phi), r * std::sin(phi), z};
  sample.normal = normalize(n);
  sample.position = center_ + sample.normal * radius_;
  sample.pdf = 1 / area();
  return true;
}

double Sphere::pdf_area(const SurfaceHit&) const {
  return 1 / area();
}

namespace {
// A reference counts as outside (cone sampling) only beyond the surface by more than rounding:
// a shading point on the sphere itself, computed a few ulps outside, is sampled by area (from
// there the cone is the tangent half-space and its points lie at the reference).
bool is_outside(double distance_squared, double radius_squared) {
  return distance_squared > radius_squared * (1 + 1e-9);
}

// 1 − cos θ_max of the cone a sphere subtends from a point at squared distance
// distance_squared > r² from its centre: sin²θ_max / (1 + cos θ_max), without cancellation.
double one_minus_cos_max(double radius_squared, double distance_squared) {
  const double sin2_max = radius_squared / distance_squared;
  const double cos_max = std::sqrt(std::max(0.0, 1 - sin2_max));
  return sin2_max / (1 + cos_max);
}
}  // namespace

bool Sphere::sample_from(const Vec3& reference, const Vec2& u, SurfaceSample& sample) const {
  const Vec3 to_center = center_ - reference;
  const double distance_squared = length_squared(to_center);
  const double radius_squared = radius_ * radius_;
  if (!is_outside(distance_squared, radius_squared)) return Shape::sample_from(reference, u, sample);
  const double distance = std::sqrt(distance_squared);
  const double sin_max = radius_ / distance;
  const double cone = one_minus_cos_max(radius_squared, distance_squared);
  // θ uniform in the cone's solid angle: 1 − cos θ = u.x (1 − cos θ_max).
  const double one_minus_cos = u.x * cone;
  const double cos_theta = 1 - one_minus_cos;
  const double sin_theta = std::sqrt(std::max(0.0, one_minus_cos * (2 - one_minus_cos)));
  // pbrt-v4: the angle α at the centre between the reference and the point on the near side.
  // In the triangle reference–centre–point the angle at the point is π − β with
  // sin β = sin θ / sin θ_max (law of sines), so α = β − θ; both its sine and cosine are
  // formed without cancellation, unlike intersecting the sampled ray with the sphere.
  const double s = std::min(1.0, sin_theta / sin_max);
  const double c = std::sqrt(std::max(0.0, 1 - s * s));
  const double cos_alpha = sin_theta * s + cos_theta * c;
  const double sin_alpha = std::max(0.0, s * cos_theta - c * sin_theta);
  const double phi = 2 * kPi * u.y;
  const Vec3 axis = to_center / distance;
  Vec3 x_axis, y_axis;
  orthonormal_basis(axis, x_axis, y_axis);
  const Vec3 n = (x_axis * std::cos(phi) + y_axis * std::sin(phi)) * sin_alpha - axis * cos_alpha;
  sample.normal = normalize(n);
  sample.position = center_ + sample.normal * radius_;
  sample.pdf = 1 / (2 * kPi * cone);
  return std::isfinite(sample.pdf);
}

double Sphere::pdf_from(const Vec3& reference, const SurfaceHit& hit) const {
  const double distance_squared = length_squared(center_ - reference);
  const double radius_squared = radius_ * radius_;
  if (!is_outside(distance_squared, radius_squared)) return Shape::pdf_from(reference, hit);
  const double pdf = 1 / (2 * kPi * one_minus_cos_max(radius_squared, distance_squared));
  return std::isfinite(pdf) ? pdf : 0;
}

}  // namespace candela
