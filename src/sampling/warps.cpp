// Warps of the unit square (see warps.h). Each forward map is a bijection of [0,1)² onto its
// domain (up to a set of measure zero), and each inverse undoes it exactly up to rounding:
//   concentric disc   Shirley & Chiu 1997, "A low distortion map between disk and square";
//   cosine hemisphere Malley's method: the concentric disc lifted to the hemisphere;
//   triangle          Heitz 2019, "A low-distortion map between triangle and square" (linear
//                     on each half of the square, so the inverse is exact);
//   Beckmann, GGX     the slope distribution's cdf in tan²θ (Walter et al. 2007, eqs. 28, 35).
#include "sampling/warps.h"

#include <algorithm>
#include <cmath>

#include "math/constants.h"

namespace candela {

namespace {

// The azimuth of (x, y) in [0, 1) of a turn.
double azimuth_fraction(double x, double y) {
  double phi = std::atan2(y, x) / (2 * kPi);
  if (phi < 0) phi += 1;
  return phi >= 1 ? 0.0 : phi;
}

Vec3 from_cos_theta(double cos_theta, double u_phi) {
  const double sin_theta = std::sqrt(std::max(0.0, 1 - cos_theta * cos_theta));
  const double phi = 2 * kPi * u_phi;
  return {sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta};
}

// tan²θ of a unit direction about +z (infinite on the horizon).
double tan2_theta(const Vec3& m) {
  const double cos2 = m.z * m.z;
  const double sin2 = std::max(0.0, m.x * m.x + m.y * m.y);
  return cos2 > 0 ? sin2 / cos2 : kInfinity;
}

}  // namespace

// --- disc --------------------------------------------------------------------------------

Vec2 square_to_uniform_disc_concentric(const Vec2& u) {
  const double a = 2 * u.x - 1, b = 2 * u.y - 1;
  if (a == 0 && b == 0) return {0, 0};
  double r, theta;
  if (std::fabs(a) > std::fabs(b)) {
    r = a;
    theta = (kPi / 4) * (b / a);
  } else {
    r = b;
    theta = kPi / 2 - (kPi / 4) * (a / b);
  }
  return {r * std::cos(theta), r * std::sin(theta)};
}

Vec2 uniform_disc_concentric_to_square(const Vec2& p) {
  const double r = std::sqrt(p.x * p.x + p.y * p.y);
  if (r == 0) return {0.5, 0.5};
  // The forward map sends the four wedges |a| > |b| (a ≷ 0) and |b| ≥ |a| (b ≷ 0) to the
  // quarter-discs of angle [−π/4, π/4), [π/4, 3π/4), [3π/4, 5π/4), [5π/4, 7π/4).
  double phi = std::atan2(p.y, p.x);
  if (phi < -kPi / 4) phi += 2 * kPi;
  double a, b;
  if (phi < kPi / 4) {
    a = r;
    b = a * phi * (4 / kPi);
  } else if (phi < 3 * kPi / 4) {
    b = r;
    a = b * (kPi / 2 - phi) * (4 / kPi);
  } else if (phi < 5 * kPi / 4) {
    a = -r;
    b = a * (phi - kPi) * (4 / kPi);
  } else {
    b = -r;
    a = b * (kPi / 2 - (phi - kPi)) * (4 / kPi);
  }
  return {(a + 1) / 2, (b + 1) / 2};
}

// --- sphere and hemisphere ---------------------------------------------------------------

Vec3 square_to_uniform_sphere(const Vec2& u) {
  return from_cos_theta(1 - 2 * u.x, u.y);
}

Vec2 uniform_sphere_to_square(const Vec3& direction) {
  return {(1 - direction.z) / 2, azimuth_fraction(direction.x, direction.y)};
}

double uniform_sphere_pdf() {
  return 1 / (4 * kPi);
}

Vec3 square_to_uniform_hemisphere(const Vec2& u) {
  return from_cos_theta(u.x, u.y);
}

Vec2 uniform_hemisphere_to_square(const Vec3& direction) {
  return {direction.z, azimuth_fraction(direction.x, direction.y)};
}

double uniform_hemisphere_pdf(const Vec3& direction) {
  return direction.z >= 0 ? 1 / (2 * kPi) : 0.0;
}

// --- cosine hemisphere -------------------------------------------------------------------

Vec3 square_to_cosine_hemisphere(const Vec2& u) {
  const Vec2 d = square_to_uniform_disc_concentric(u);
  return {d.x, d.y, std::sqrt(std::max(0.0, 1 - d.x * d.x - d.y * d.y))};
}

Vec2 cosine_hemisphere_to_square(const Vec3& direction) {
  return uniform_disc_concentric_to_square({direction.x, direction.y});
}

double cosine_hemisphere_pdf(const Vec3& direction) {
  return direction.z > 0 ? direction.z * kInvPi : 0.0;
}

// --- cone --------------------------------------------------------------------------------

Vec3 square_to_uniform_cone(const Vec2& u, double cos_max) {
  return from_cos_theta(1 - u.x * (1 - cos_max), u.y);
}

Vec2 uniform_cone_to_square(const Vec3& direction, double cos_max) {
  return {(1 - direction.z) / (1 - cos_max), azimuth_fraction(direction.x, direction.y)};
}

double uniform_cone_pdf(const Vec3& direction, double cos_max) {
  return direction.z >= cos_max ? 1 / (2 * kPi * (1 - cos_max)) : 0.0;
}

// --- power cosine ------------------------------------------------------------------------

// P(cos θ ≤ c) = c^(n+1) under the density (n + 1)/(2π) cos^n θ, so cos θ = u^(1/(n+1)).
Vec3 square_to_power_cosine(const Vec2& u, double exponent) {
  return from_cos_theta(std::pow(u.x, 1 / (exponent + 1)), u.y);
}

Vec2 power_cosine_to_square(const Vec3& direction, double exponent) {
  return {std::pow(std::max(0.0, direction.z), exponent + 1), azimuth_fraction(direction.x, direction.y)};
}

double power_cosine_pdf(const Vec3& direction, double exponent) {
  if (!(direction.z > 0)) return 0;
  return (exponent + 1) / (2 * kPi) * std::pow(direction.z, exponent);
}

// --- triangle ----------------------------------------------------------------------------

// Heitz 2019: the half u.y > u.x shears onto b1 > b0, the other half onto b0 ≥ b1; both maps
// are linear with Jacobian ½, so the density on the triangle is uniform.
Vec2 square_to_uniform_triangle(const Vec2& u) {
  if (u.y > u.x) {
    const double b0 = u.x / 2;
    return {b0, u.y - b0};
  }
  const double b1 = u.y / 2;
  return {u.x - b1, b1};
}

Vec2 uniform_triangle_to_square(const Vec2& barycentric) {
  const double b0 = barycentric.x, b1 = barycentric.y;
  if (b1 > b0) return {2 * b0, b1 + b0};
  return {b0 + b1, 2 * b1};
}

// --- microfacet normals ------------------------------------------------------------------

// Beckmann: D(m) = exp(−tan²θ/α²)/(πα² cos⁴θ); the density of tan²θ under D·cosθ is
// exp(−t/α²)/α², so t = −α² ln(1 − u).
Vec3 square_to_beckmann(const Vec2& u, double alpha) {
  const double tan2 = -alpha * alpha * std::log1p(-u.x);
  return from_cos_theta(1 / std::sqrt(1 + tan2), u.y);
}

Vec2 beckmann_to_square(const Vec3& m, double alpha) {
  return {-std::expm1(-tan2_theta(m) / (alpha * alpha)), azimuth_fraction(m.x, m.y)};
}

double beckmann_pdf(const Vec3& m, double alpha) {
  if (!(m.z > 0)) return 0;
  const double cos2 = m.z * m.z;
  const double exponent = tan2_theta(m) / (alpha * alpha);
  if (exponent > 700) return 0;                                     // e^-700 underflows; cos⁴ may too (0/0)
  return std::exp(-exponent) / (kPi * alpha * alpha * cos2 * m.z);  // D·cosθ
}

// GGX: D(m) = α²/(π cos⁴θ (α² + tan²θ)²); the cdf of tan²θ is t/(α² + t), so t = α²u/(1 − u).
Vec3 square_to_ggx(const Vec2& u, double alpha) {
  const double tan2 = alpha * alpha * u.x / (1 - u.x);
  return from_cos_theta(1 / std::sqrt(1 + tan2), u.y);
}

Vec2 ggx_to_square(const Vec3& m, double alpha) {
  const double tan2 = tan2_theta(m);
  const double ux = std::isinf(tan2) ? 1.0 : tan2 / (alpha * alpha + tan2);
  return {ux, azimuth_fraction(m.x, m.y)};
}

double ggx_pdf(const Vec3& m, double alpha) {
  if (!(m.z > 0)) return 0;
  const double a2 = alpha * alpha;
  // D·cosθ = α² cosθ / (π (α² cos²θ + sin²θ)²), free of tan θ near the horizon.
  const double cos2 = m.z * m.z;
  const double sin2 = std::max(0.0, 1 - cos2);
  const double denominator = a2 * cos2 + sin2;
  return a2 * m.z / (kPi * denominator * denominator);
}

// The inverse of the CDF x ↦ (a x + (b − a) x²/2) / ((a + b)/2) in the form that stays exact
// when a ≈ b: x = u (a + b) / (a + √((1 − u) a² + u b²)).
double sample_linear(double u, double a, double b) {
  if (u == 0 && a == 0) return 0;
  const double x = u * (a + b) / (a + std::sqrt((1 - u) * a * a + u * b * b));
  return std::min(x, 0x1.fffffffffffffp-1);
}

double linear_to_square(double x, double a, double b) {
  return x * (a * (2 - x) + b * x) / (a + b);
}

Vec2 square_to_bilinear(const Vec2& u, const double (&w)[4]) {
  // The second coordinate by its marginal (the first's weights summed), then the first given it.
  const double y = sample_linear(u.y, w[0] + w[1], w[2] + w[3]);
  const double x = sample_linear(u.x, (1 - y) * w[0] + y * w[2], (1 - y) * w[1] + y * w[3]);
  return {x, y};
}

Vec2 bilinear_to_square(const Vec2& p, const double (&w)[4]) {
  return {linear_to_square(p.x, (1 - p.y) * w[0] + p.y * w[2], (1 - p.y) * w[1] + p.y * w[3]),
          linear_to_square(p.y, w[0] + w[1], w[2] + w[3])};
}

double bilinear_pdf(const Vec2& p, const double (&w)[4]) {
  const double sum = w[0] + w[1] + w[2] + w[3];
  if (!(sum > 0) || p.x < 0 || p.x > 1 || p.y < 0 || p.y > 1) return 0;
  return 4 *
         ((1 - p.x) * (1 - p.y) * w[0] + p.x * (1 - p.y) * w[1] + (1 - p.x) * p.y * w[2] + p.x * p.y * w[3]) /
         sum;
}

}  // namespace candela
