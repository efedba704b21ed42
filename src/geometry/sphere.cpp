#include "geometry/sphere.h"

#include <cmath>
#include <stdexcept>

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

}  // namespace candela
