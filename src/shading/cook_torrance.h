// The Cook-Torrance specular term (000 §4.2.2; SPEC §7; Cook & Torrance 1982):
//   k_s = D·G·F / (π (N·V)(N·L))
// D: Beckmann's facet distribution with rms slope m, as in Cook and Torrance's paper,
//    D = exp(−(tan α / m)²) / (m² cos⁴ α), α the angle between N and H — without the 1/π of
//    the normalised Beckmann distribution of pbrt and Mitsuba (∫D cos α dω = π here), which
//    the π in the denominator of k_s accounts for;
// G: masking and shadowing, G = min(1, 2(N·H)(N·V)/(V·H), 2(N·H)(N·L)/(V·H));
// F: the unpolarised Fresnel reflectance (000 §4.2.2, ½[sin²(φ−θ)/sin²(φ+θ) +
//    tan²(φ−θ)/tan²(φ+θ)]) at the angle θ between V and H, with an index of refraction per RGB
//    channel, so the highlight takes the material's color.
#pragma once

#include "math/vector.h"

namespace candela {

double beckmann_distribution(double cos_alpha, double m);
double geometric_attenuation(double n_dot_h, double n_dot_v, double n_dot_l, double v_dot_h);
// cos_theta: cosine of the angle of incidence (> 0); n: relative index of refraction (> 0).
// Equals ((n − 1)/(n + 1))² at normal incidence and 1 at grazing incidence.
double fresnel_unpolarized(double cos_theta, double n);
Color fresnel_unpolarized(double cos_theta, const Color& n);

// k_s of the formula above for unit N, V, L (0 where N·V ≤ 0 or N·L ≤ 0).
Color cook_torrance(const Vec3& N, const Vec3& V, const Vec3& L, double m, const Color& ior);

}  // namespace candela
