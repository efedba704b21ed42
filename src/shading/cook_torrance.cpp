#include "shading/cook_torrance.h"

#include <algorithm>
#include <cmath>

#include "math/constants.h"

namespace candela {

double beckmann_distribution(double cos_alpha, double m) {
  if (!(cos_alpha > 0)) return 0;
  const double cos2 = cos_alpha * cos_alpha;
  const double tan2 = (1 - cos2) / cos2;
  const double exponent = tan2 / (m * m);
  // Past e^-700 the value is 0 in double, and cos⁴ may underflow too (0/0 at grazing facets).
  if (exponent > 700) return 0;
  return std::exp(-exponent) / (m * m * cos2 * cos2);
}

double geometric_attenuation(double n_dot_h, double n_dot_v, double n_dot_l, double v_dot_h) {
  if (!(v_dot_h > 0)) return 0;
  return std::min({1.0, 2 * n_dot_h * n_dot_v / v_dot_h, 2 * n_dot_h * n_dot_l / v_dot_h});
}

Color cook_torrance(const Vec3& N, const Vec3& V, const Vec3& L, double m, const Fresnel& fresnel) {
  const double n_dot_v = dot(N, V);
  const double n_dot_l = dot(N, L);
  if (!(n_dot_v > 0) || !(n_dot_l > 0)) return {};
  const Vec3 half = L + V;
  const double half_length = length(half);
  if (!(half_length > 0)) return {};
  const Vec3 H = half / half_length;
  const double n_dot_h = dot(N, H);
  const double v_dot_h = dot(V, H);
  const double D = beckmann_distribution(n_dot_h, m);
  const double G = geometric_attenuation(n_dot_h, n_dot_v, n_dot_l, v_dot_h);
  return fresnel.reflectance(v_dot_h) * (D * G / (kPi * n_dot_v * n_dot_l));
}

}  // namespace candela
