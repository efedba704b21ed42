#include "shading/fresnel.h"

#include <algorithm>
#include <cmath>

namespace candela {

double fresnel_unpolarized(double cos_theta, double n) {
  // Cook & Torrance's form of the seed's formula: with c = cos θ and g² = n² + c² − 1
  // (g = n cos φ by Snell's law), F = ½ (g−c)²/(g+c)² · [1 + (c(g+c) − 1)² / (c(g−c) + 1)²].
  const double c = std::clamp(cos_theta, 0.0, 1.0);
  const double g2 = n * n + c * c - 1;
  if (g2 <= 0) return 1;  // total internal reflection (n < 1 past the critical angle)
  const double g = std::sqrt(g2);
  const double a = (g - c) / (g + c);
  const double b = (c * (g + c) - 1) / (c * (g - c) + 1);
  return 0.5 * a * a * (1 + b * b);
}

Color fresnel_unpolarized(double cos_theta, const Color& n) {
  return {fresnel_unpolarized(cos_theta, n.r), fresnel_unpolarized(cos_theta, n.g),
          fresnel_unpolarized(cos_theta, n.b)};
}

SheetSplit thin_sheet(double cos_theta, double n, double transmissivity) {
  // With g = n cos θ_t (Snell's law, as above): r_s = ((c − g)/(c + g))², r_p = ((n² c − g)/(n² c + g))².
  const double c = std::clamp(cos_theta, 0.0, 1.0);
  const double g2 = n * n + c * c - 1;
  if (g2 <= 0 || c == 0) return {1, 0};
  const double g = std::sqrt(g2);
  const double t =
      transmissivity >= 1 ? 1.0 : std::pow(std::max(transmissivity, 0.0), n / g);  // 1/cos θ_t = n/g
  SheetSplit split;
  for (const double amplitude : {(c - g) / (c + g), (n * n * c - g) / (n * n * c + g)}) {
    const double r = amplitude * amplitude, rt = r * t, denominator = 1 - rt * rt;
    split.reflectance += 0.5 * (r + (1 - r) * (1 - r) * r * t * t / denominator);
    split.transmittance += 0.5 * (1 - r) * (1 - r) * t / denominator;
  }
  return split;
}

SheetColors thin_sheet(double cos_theta, double n, const Color& transmissivity) {
  SheetColors colors;
  for (int c = 0; c < 3; ++c) {
    const SheetSplit split = thin_sheet(cos_theta, n, transmissivity[c]);
    colors.reflectance[c] = split.reflectance;
    colors.transmittance[c] = split.transmittance;
  }
  return colors;
}

double fresnel_conductor(double cos_theta, double n, double k) {
  // With a² − b² = n² − κ² − sin²θ and a² + b² = √((n² − κ² − sin²θ)² + 4n²κ²):
  //   R_s = (a² + b² − 2a cos θ + cos²θ) / (a² + b² + 2a cos θ + cos²θ),
  //   R_p = R_s (cos²θ (a² + b²) − 2a cos θ sin²θ + sin⁴θ) / (cos²θ (a² + b²) + 2a cos θ sin²θ + sin⁴θ).
  const double c = std::clamp(cos_theta, 0.0, 1.0);
  const double cos2 = c * c;
  const double sin2 = 1 - cos2;
  const double t0 = n * n - k * k - sin2;
  const double a2_plus_b2 = std::sqrt(t0 * t0 + 4 * n * n * k * k);
  const double a = std::sqrt(std::max(0.0, 0.5 * (a2_plus_b2 + t0)));
  const double t1 = a2_plus_b2 + cos2;
  const double t2 = 2 * c * a;
  if (!(t1 + t2 > 0)) return 1;  // grazing incidence on n = κ = 0
  const double rs = (t1 - t2) / (t1 + t2);
  const double t3 = cos2 * a2_plus_b2 + sin2 * sin2;
  const double t4 = t2 * sin2;
  const double rp = t3 + t4 > 0 ? rs * (t3 - t4) / (t3 + t4) : rs;
  return 0.5 * (rs + rp);
}

double fresnel_schlick(double cos_theta, double f0) {
  const double m = 1 - std::clamp(cos_theta, 0.0, 1.0);
  const double m2 = m * m;
  return f0 + (1 - f0) * m2 * m2 * m;
}

Fresnel Fresnel::dielectric(const Color& eta) {
  Fresnel fresnel;
  fresnel.eta = eta;
  return fresnel;
}

Fresnel Fresnel::conductor(const Color& eta, const Color& k) {
  Fresnel fresnel;
  fresnel.model = FresnelModel::conductor;
  fresnel.eta = eta;
  fresnel.k = k;
  return fresnel;
}

Fresnel Fresnel::schlick(const Color& f0) {
  Fresnel fresnel;
  fresnel.model = FresnelModel::schlick;
  fresnel.f0 = f0;
  return fresnel;
}

Color Fresnel::reflectance(double cos_theta) const {
  Color F;
  for (int c = 0; c < 3; ++c) {
    switch (model) {
      case FresnelModel::dielectric:
        F[c] = fresnel_unpolarized(cos_theta, eta[c]);
        break;
      case FresnelModel::conductor:
        F[c] = fresnel_conductor(cos_theta, eta[c], k[c]);
        break;
      case FresnelModel::schlick:
        F[c] = fresnel_schlick(cos_theta, f0[c]);
        break;
    }
  }
  return F;
}

}  // namespace candela
