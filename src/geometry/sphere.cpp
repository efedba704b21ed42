#include "geometry/sphere.h"

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
  hit.dpdv =
      Vec3{local.z * std::cos(phi), local.z * std::sin(phi), -std::sin(theta)} * (-kPi * radius_);
  return true;
}

bool Sphere::occluded(const Ray& ray) const { return nearest_t(ray) >= 0; }

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
  std::vector<std::vector<Vec3>> rings(bands + 1);
  for (int j = 0; j <= bands; ++j) {
    const double theta = kPi * (1.0 - static_cast<double>(j) / bands);
    const double cos_theta = j == 0 ? -1.0 : (j == bands ? 1.0 : std::cos(theta));
    const double sin_theta = (j == 0 || j == bands) ? 0.0 : std::sin(theta);
    rings[j] = circle_points(center_ + Vec3{0, 0, radius_ * cos_theta}, {1, 0, 0}, {0, 1, 0},
                             radius_ * sin_theta, circle);
  }
  append_revolution_grid(rings, /*wrap_rings=*/false, out);
}

}  // namespace candela
