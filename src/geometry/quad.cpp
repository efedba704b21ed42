#include "geometry/quad.h"

#include <immintrin.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "geometry/flat_surface.h"
#include "geometry/tessellation.h"
#include "sampling/warps.h"

namespace candela {

// Within twice its diagonal of the quad's centre the solid-angle density varies over the quad and
// the warp pays; farther out the corners' weights differ less and uniform points cost less (the
// Cornell box, 128², variance × time of the walls: 0.94× uniform sampling's with this distance,
// 0.96× at three diagonals, 0.98× with the warp everywhere).
constexpr double kWarpDiagonals = 2;

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
  warp_distance_squared_ =
      kWarpDiagonals * kWarpDiagonals * (length_squared(edge_u) + length_squared(edge_v));
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

// The weights are relative (the warp normalises them), so they are (d_min² / d²)^(3/2): the
// height, common to every corner, drops out, and no scene scale overflows a float. Four lanes in
// one SSE division and square root (exact IEEE operations: the same bits on every x86-64).
bool Quad::seen_from(const Vec3& reference, CornerWeights& weights) const {
  // n·(corner − reference) is the same at every point of the plane: the reference's height.
  const Vec3 to_corner = corner_ - reference;
  weights.height = std::fabs(dot(normal_, to_corner));
  if (!(weights.height > 0)) return false;
  weights.warped = length_squared(to_corner + (edge_u_ + edge_v_) * 0.5) < warp_distance_squared_;
  if (!weights.warped) return true;
  const double d2[4] = {length_squared(to_corner), length_squared(to_corner + edge_u_),
                        length_squared(to_corner + edge_v_), length_squared(to_corner + edge_u_ + edge_v_)};
  const double nearest = std::min(std::min(d2[0], d2[1]), std::min(d2[2], d2[3]));
  const __m128 ratio = _mm_div_ps(_mm_set1_ps(static_cast<float>(nearest)),
                                  _mm_setr_ps(static_cast<float>(d2[0]), static_cast<float>(d2[1]),
                                              static_cast<float>(d2[2]), static_cast<float>(d2[3])));
  alignas(16) float w[4];
  _mm_store_ps(w, _mm_mul_ps(ratio, _mm_sqrt_ps(ratio)));
  double sum = 0;
  for (int i = 0; i < 4; ++i) sum += weights.w[i] = w[i];
  // A distance that a float cannot hold: uniform.
  if (!(sum > 0) || !std::isfinite(sum)) weights.warped = false;
  return true;
}

// |cos θ| / d² = height / d³ at every point of the plane.
double Quad::solid_angle_pdf(const Vec3& reference, const Vec2& uv, const Vec3& position,
                             const CornerWeights& weights) const {
  const double d2 = length_squared(position - reference);
  const double area_density = (weights.warped ? bilinear_pdf(uv, weights.w) : 1.0) / area_;
  const double pdf = area_density * d2 * std::sqrt(d2) / weights.height;
  return std::isfinite(pdf) && pdf > 0 ? pdf : 0;
}

bool Quad::sample_from(const Vec3& reference, const Vec2& u, SurfaceSample& sample) const {
  CornerWeights weights;
  if (!seen_from(reference, weights)) return false;
  const Vec2 uv = weights.warped ? square_to_bilinear(u, weights.w) : u;
  sample.position = corner_ + edge_u_ * uv.x + edge_v_ * uv.y;
  sample.normal = normal_;
  sample.pdf = solid_angle_pdf(reference, uv, sample.position, weights);
  return sample.pdf > 0;
}

double Quad::pdf_from(const Vec3& reference, const SurfaceHit& hit) const {
  CornerWeights weights;
  if (!seen_from(reference, weights)) return 0;
  return solid_angle_pdf(reference, hit.uv, hit.position, weights);
}

}  // namespace candela
