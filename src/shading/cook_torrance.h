// The Cook-Torrance specular term (000 §4.2.2; SPEC §7; Cook & Torrance 1982):
//   k_s = D·G·F / (π (N·V)(N·L))
// D: Beckmann's facet distribution with rms slope m, as in Cook and Torrance's paper,
//    D = exp(−(tan α / m)²) / (m² cos⁴ α), α the angle between N and H — without the 1/π of
//    the normalised Beckmann distribution of pbrt and Mitsuba (∫D cos α dω = π here), which
//    the π in the denominator of k_s accounts for;
// G: masking and shadowing, G = min(1, 2(N·H)(N·V)/(V·H), 2(N·H)(N·L)/(V·H));
// F: the Fresnel reflectance at the angle θ between V and H (shading/fresnel.h: the seed's
//    unpolarised dielectric of 000 §4.2.2, a conductor's complex index, or Schlick's form of a
//    measured F0), per RGB channel, so the highlight takes the material's color.
#pragma once

#include "math/vector.h"
#include "shading/fresnel.h"

namespace candela {

double beckmann_distribution(double cos_alpha, double m);
double geometric_attenuation(double n_dot_h, double n_dot_v, double n_dot_l, double v_dot_h);

// k_s of the formula above for unit N, V, L (0 where N·V ≤ 0 or N·L ≤ 0).
Color cook_torrance(const Vec3& N, const Vec3& V, const Vec3& L, double m, const Fresnel& fresnel);

}  // namespace candela
