#include "geometry/quad.h"

#include <cmath>
#include <stdexcept>

#include "geometry/flat_surface.h"
#include "geometry/tessellation.h"
#include "sampling/warps.h"

namespace candela {

Quad::Quad(const Vec3& corner, const Vec3& edge_u, const Vec3& edge_v)
    : corner_(corner), edge_u_(edge_u), edge_v_(edge_v) {
  if (!is_finite(corner) || !is_finite(edge_u) || !is_finite(edge_v))
    throw std::invalid_argument("corner and edges must be finite");
  const Vec3 n = cross(edge_u, edge_v);
  area_ = length(n);
  // Relative test: edges parallel to within rounding span no area.
  if (!(area_ > 1e-12 * length(edge_u) * length(edge_v)) || !std::isfinite(area_))
    throw std::invalid_argument("edge_u and edge_v must be non-zero and not parallel");
  normal_ = n / area_;
  // For p − corner = u·e_u + v·e_v: u = ((p − c) × e_v)·n / |n|², v = (e_u × (p − c))·n / |n|²,
  // i.e. u = (p − c)·(e_v × n)/|n|² and v = (p − c)·(n × e_u)/|n|².
  dual_u_ = cross(edge_v, n) / (area_ * area_);
  dual_v_ = cross(n, edge_u) / (area_ * area_);
}

double Quad::nearest_t(const Ray& ray, double& u, double& v) const {
  const double t = plane_hit_distance(ray, corner_, normal_);
  if (t == kInfinity) return kInfinity;
  const Vec3 offset = ray.at(t) - corner_;
  u = dot(offset, dual_u_);
  v = dot(offset, dual_v_);
  if (!(u >= 0 && u <= 1 && v >= 0 && v <= 1)) return kInfinity;
  return t;
}

bool Quad::intersect(const Ray& ray, SurfaceHit& hit) const {
  double u, v;
  const double t = nearest_t(ray, u, v);
  if (t == kInfinity) return false;
  fill_flat_hit(ray, t, normal_, hit);
  hit.uv = {u, v};
  hit.dpdu = edge_u_;
  hit.dpdv = edge_v_;
  return true;
}

bool Quad::occluded(const Ray& ray) const {
  double u, v;
  return nearest_t(ray, u, v) < kInfinity;
}

Bounds3 Quad::bounds() const {
  Bounds3 b = Bounds3::of_point(corner_);
  b.extend(corner_ + edge_u_);
  b.extend(corner_ + edge_v_);
  b.extend(corner_ + edge_u_ + edge_v_);
  return b;
}

void Quad::tessellate(const TessellationSettings&, TriangleMesh& mesh) const {
  MeshAppender out(mesh);
  // Counter-clockwise in (u, v), so about edge_u × edge_v, the normal.
  const uint32_t origin = out.vertex(corner_), along_u = out.vertex(corner_ + edge_u_),
                 opposite = out.vertex(corner_ + edge_u_ + edge_v_), along_v = out.vertex(corner_ + edge_v_);
  out.triangle({origin, along_u, opposite}, {Vec2{0, 0}, Vec2{1, 0}, Vec2{1, 1}});
  out.triangle({origin, opposite, along_v}, {Vec2{0, 0}, Vec2{1, 1}, Vec2{0, 1}});
}

bool Quad::sample_area(const Vec2& u, SurfaceSample& sample) const {
  sample.position = corner_ + edge_u_ * u.x + edge_v_ * u.y;
  sample.normal = normal_;
  sample.pdf = 1 / area_;
  return true;
}

double Quad::pdf_area(const SurfaceHit&) const {
  return 1 / area_;
}

bool Quad::corner_weights(const Vec3& reference, double (&w)[4]) const {
  // n·(corner − reference) is the same at every corner: the reference's height over the plane.
  const double height = std::fabs(dot(normal_, corner_ - reference));
  if (!(height > 0)) return false;
  const Vec3 corners[4] = {corner_, corner_ + edge_u_, corner_ + edge_v_, corner_ + edge_u_ + edge_v_};
  double sum = 0;
  for (int i = 0; i < 4; ++i) {
    const double d2 = length_squared(corners[i] - reference);
    w[i] = height / (d2 * std::sqrt(d2));  // cos θ / d²
    sum += w[i];
  }
  if (!std::isfinite(sum) || !(sum > 0))  // a corner at (or all corners too near) the reference
    for (double& weight : w) weight = 1;
  return true;
}

double Quad::solid_angle_pdf(const Vec3& reference, const Vec2& uv, const Vec3& position,
                             const double (&w)[4]) const {
  const Vec3 to_point = position - reference;
  const double d2 = length_squared(to_point);
  const double cos_light = std::fabs(dot(normal_, to_point)) / std::sqrt(d2);
  const double pdf = bilinear_pdf(uv, w) / area_ * d2 / cos_light;
  return std::isfinite(pdf) && pdf > 0 ? pdf : 0;
}

bool Quad::sample_from(const Vec3& reference, const Vec2& u, SurfaceSample& sample) const {
  double w[4];
  if (!corner_weights(reference, w)) return false;
  const Vec2 uv = square_to_bilinear(u, w);
  sample.position = corner_ + edge_u_ * uv.x + edge_v_ * uv.y;
  sample.normal = normal_;
  sample.pdf = solid_angle_pdf(reference, uv, sample.position, w);
  return sample.pdf > 0;
}

double Quad::pdf_from(const Vec3& reference, const SurfaceHit& hit) const {
  double w[4];
  if (!corner_weights(reference, w)) return 0;
  return solid_angle_pdf(reference, hit.uv, hit.position, w);
}

}  // namespace candela
