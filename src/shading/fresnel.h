// Fresnel reflectance F(cos θ) of a smooth interface, per RGB channel (000 §4.2.2; SPEC §7):
//   dielectric  the unpolarised reflectance of a real index n (000 §4.2.2, ½[sin²(φ−θ)/sin²(φ+θ) +
//               tan²(φ−θ)/tan²(φ+θ)]): glass, plastic, water;
//   conductor   the unpolarised reflectance of a complex index n + iκ (Born & Wolf §14.2; the
//               form of pbrt-v3's FrConductor): a metal, which whitens toward grazing incidence;
//   schlick     F0 + (1 − F0)(1 − cos θ)⁵ (Schlick 1994) for a measured reflectance F0 at normal
//               incidence.
// A metal given only F0 must not become a dielectric of index (1 + √F0)/(1 − √F0), as Cook and
// Torrance did: with no extinction that index has a Brewster dip, the deeper the larger F0, so
// F0 [0.95, 0.64, 0.54] (copper) reflects [0.68, 0.55, 0.60] at 87° — bluish instead of white.
#pragma once

#include <cstdint>

#include "math/vector.h"

namespace candela {

// cos_theta: cosine of the angle of incidence (clamped to [0, 1]); n: relative index (> 0).
// Equals ((n − 1)/(n + 1))² at normal incidence and 1 at grazing incidence (and past the critical
// angle when n < 1).
double fresnel_unpolarized(double cos_theta, double n);
Color fresnel_unpolarized(double cos_theta, const Color& n);
// n + iκ, κ ≥ 0 the extinction coefficient; equals fresnel_unpolarized(cos_theta, n) when κ = 0
// and n ≥ 1, and ((n − 1)² + κ²)/((n + 1)² + κ²) at normal incidence.
double fresnel_conductor(double cos_theta, double n, double k);
double fresnel_schlick(double cos_theta, double f0);
// A thin sheet of relative index n (a window pane) seen at incidence cos_theta, whose one pass at
// normal incidence lets `transmissivity` through (the internal transmittance: Radiance's glass
// "transmissivity"; 1 lossless). Each polarisation's interface reflectance r bounces between the
// two faces, and a pass at refraction angle θ_t lets t = transmissivity^(1/cos θ_t) through:
//   R = r + (1 − r)² r t² / (1 − r² t²),   T = (1 − r)² t / (1 − r² t²)
// (the incoherent sum of the internal reflections, Born & Wolf §1.6; lossless: R = 2r/(1 + r),
// T = (1 − r)/(1 + r), pbrt-v4's ThinDielectricBxDF), the unpolarised mean of the two. n = 1.5,
// lossless: 0.0769 reflected at normal incidence; n = 1.52 and 0.95712 give CIE 171's 6 mm clear
// glass, 0.87881 through at normal incidence.
struct SheetSplit {
  double reflectance = 0, transmittance = 0;
};
SheetSplit thin_sheet(double cos_theta, double n, double transmissivity = 1);
struct SheetColors {
  Color reflectance, transmittance;
};
SheetColors thin_sheet(double cos_theta, double n, const Color& transmissivity);

enum class FresnelModel : uint8_t { dielectric, conductor, schlick };

// The Fresnel factor of a microfacet lobe (the local model's Cook-Torrance term, the path
// tracer's microfacet lobe): a plain value.
struct Fresnel {
  FresnelModel model = FresnelModel::dielectric;
  Color eta{1.5, 1.5, 1.5};  // dielectric, conductor: the real part n per channel
  Color k;                   // conductor: the extinction coefficient κ per channel
  Color f0;                  // schlick: the reflectance at normal incidence per channel

  static Fresnel dielectric(const Color& eta);
  static Fresnel conductor(const Color& eta, const Color& k);
  static Fresnel schlick(const Color& f0);
  Color reflectance(double cos_theta) const;
  bool operator==(const Fresnel&) const = default;
};

}  // namespace candela
