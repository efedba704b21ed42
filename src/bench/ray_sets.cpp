#include "bench/ray_sets.h"

#include <algorithm>
#include <cmath>

#include "math/constants.h"

namespace candela {

namespace {

BenchRay make_ray(const Vec3& origin, const Vec3& direction, double t_near, double t_far) {
  BenchRay ray;
  for (int axis = 0; axis < 3; ++axis) {
    ray.origin[axis] = static_cast<float>(origin[axis]);
    ray.direction[axis] = static_cast<float>(direction[axis]);
  }
  ray.t_near = static_cast<float>(t_near);
  ray.t_far = static_cast<float>(t_far);
  return ray;
}

Vec3 origin_of(const BenchRay& ray) {
  return {ray.origin[0], ray.origin[1], ray.origin[2]};
}
Vec3 direction_of(const BenchRay& ray) {
  return {ray.direction[0], ray.direction[1], ray.direction[2]};
}

}  // namespace

[[gnu::noinline]] double round_to_float32(double x) {
  return static_cast<double>(static_cast<float>(x));
}

Ray to_ray(const BenchRay& ray) {
  Ray result;
  result.origin = origin_of(ray);
  result.direction = direction_of(ray);
  result.t_min = ray.t_near;
  result.t_max = ray.t_far;
  return result;
}

BenchView resolve_view(const Bounds3& bounds, const RaySetOptions& options) {
  BenchView view;
  const Vec3 centre = (bounds.lower + bounds.upper) * 0.5;
  view.diagonal = length(bounds.upper - bounds.lower);
  view.lookat = options.lookat ? *options.lookat : centre;
  view.eye = options.eye ? *options.eye : centre + 0.8 * view.diagonal * normalize(Vec3{0.6, 0.45, 1.0});
  view.light = options.light ? *options.light : centre + view.diagonal * Vec3{0.3, 1.0, 0.5};
  return view;
}

std::vector<BenchRay> primary_rays(const Bounds3& bounds, const RaySetOptions& options) {
  const BenchView view = resolve_view(bounds, options);
  const Vec3 forward = normalize(view.lookat - view.eye);
  const Vec3 right = normalize(cross(forward, Vec3{0, 1, 0}));
  const Vec3 up = cross(right, forward);
  const double h = std::tan(degrees_to_radians(options.fov_degrees) / 2.0);
  const double aspect = static_cast<double>(options.width) / static_cast<double>(options.height);
  std::vector<BenchRay> rays;
  rays.reserve(static_cast<std::size_t>(options.width) * static_cast<std::size_t>(options.height));
  for (int y = 0; y < options.height; ++y)
    for (int x = 0; x < options.width; ++x) {
      const double u = (2.0 * (x + 0.5) / options.width - 1.0) * h * aspect;
      const double v = (1.0 - 2.0 * (y + 0.5) / options.height) * h;
      rays.push_back(make_ray(view.eye, normalize(u * right + v * up + forward), 0.0, kInfinity));
    }
  return rays;
}

std::vector<BenchRay> incoherent_rays(const Bounds3& bounds, uint64_t count, uint64_t seed) {
  SplitMix64 random(seed);
  const Vec3 extent = bounds.upper - bounds.lower;
  std::vector<BenchRay> rays;
  rays.reserve(static_cast<std::size_t>(count));
  for (uint64_t i = 0; i < count; ++i) {
    const double a = random.uniform(), b = random.uniform(), c = random.uniform();
    const double u1 = random.uniform(), u2 = random.uniform();
    const Vec3 origin = bounds.lower + Vec3{extent.x * a, extent.y * b, extent.z * c};
    const double z = 1.0 - 2.0 * u1;
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    const double phi = 2.0 * kPi * u2;
    rays.push_back(make_ray(origin, Vec3{r * std::cos(phi), r * std::sin(phi), z}, 0.0, kInfinity));
  }
  return rays;
}

std::vector<BenchRay> shadow_rays(const Bounds3& bounds, const RaySetOptions& options,
                                  std::span<const BenchRay> primary, std::span<const double> hit_t) {
  const BenchView view = resolve_view(bounds, options);
  const double epsilon = 1e-4 * view.diagonal;
  std::vector<BenchRay> rays;
  for (std::size_t i = 0; i < primary.size() && i < hit_t.size(); ++i) {
    const double t = hit_t[i];
    if (!std::isfinite(t)) continue;
    const Vec3 p = origin_of(primary[i]) + t * direction_of(primary[i]);
    const Vec3 to_light = view.light - p;
    const double distance = length(to_light);
    rays.push_back(make_ray(p, to_light / distance, epsilon, std::max(epsilon, distance - epsilon)));
  }
  return rays;
}

}  // namespace candela
