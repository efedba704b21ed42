#include "shading/photometric_units.h"

#include <algorithm>
#include <cmath>

namespace candela {

namespace {

// Wyman, Sloan and Shirley 2013, "Simple Analytic Approximations to the CIE XYZ Color Matching
// Functions", the multi-lobe fit: a sum of piecewise Gaussians, σ₁ left of the peak, σ₂ right.
double lobe(double lambda, double peak, double sigma_left, double sigma_right) {
  const double t = (lambda - peak) / (lambda < peak ? sigma_left : sigma_right);
  return std::exp(-0.5 * t * t);
}

Vec3 cie_xyz(double lambda) {
  const double x = 1.056 * lobe(lambda, 599.8, 37.9, 31.0) + 0.362 * lobe(lambda, 442.0, 16.0, 26.7) -
                   0.065 * lobe(lambda, 501.1, 20.4, 26.2);
  const double y = 0.821 * lobe(lambda, 568.8, 46.9, 40.5) + 0.286 * lobe(lambda, 530.9, 16.3, 31.1);
  const double z = 1.217 * lobe(lambda, 437.0, 11.8, 36.0) + 0.681 * lobe(lambda, 459.0, 26.0, 13.8);
  return {x, y, z};
}

}  // namespace

Color blackbody_color(double kelvin) {
  kelvin = std::clamp(kelvin, 1000.0, 40000.0);
  // Planck's law up to a constant: λ⁻⁵ / (exp(hc / λkT) − 1), λ in nm; hc/k = 1.4388e7 nm·K.
  Vec3 xyz;
  for (int nm = 360; nm <= 830; ++nm) {
    const double lambda = nm;
    const double planck = 1 / (std::pow(lambda, 5) * std::expm1(1.4388e7 / (lambda * kelvin)));
    xyz += cie_xyz(lambda) * planck;
  }
  // XYZ to linear Rec. 709 (sRGB primaries, D65 white; IEC 61966-2-1).
  Color rgb(3.2404542 * xyz.x - 1.5371385 * xyz.y - 0.4985314 * xyz.z,
            -0.9692660 * xyz.x + 1.8760108 * xyz.y + 0.0415560 * xyz.z,
            0.0556434 * xyz.x - 0.2040259 * xyz.y + 1.0572252 * xyz.z);
  for (int c = 0; c < 3; ++c) rgb[c] = std::max(0.0, rgb[c]);
  return unit_luminance(rgb);
}

}  // namespace candela
