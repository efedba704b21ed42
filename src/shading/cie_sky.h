// The CIE standard general sky (ISO 15469:2004 / CIE S 011/E:2003): fifteen
// relative luminance distributions from the heavily overcast to the cloudless sky, each the
// product of a gradation function of the zenith angle Z and a scattering indicatrix of the
// angular distance χ to the sun:
//   L(Z, χ) / L_zenith = f(χ) φ(Z) / (f(Z_s) φ(0)),
//   φ(Z) = 1 + a exp(b / cos Z) (φ = 1 at the horizon), f(χ) = 1 + c (exp(dχ) − exp(dπ/2)) + e cos² χ,
// with (a, b) of six gradation groups and (c, d, e) of six indicatrix groups (the standard's
// Table 1). Type 1 is the CIE standard overcast sky (L at the horizon ≈ L_zenith / 3, as
// Moon and Spencer's (1 + 2 cos Z)/3), type 12 the CIE standard clear sky.
#pragma once

namespace candela {

// The sky's luminance relative to its zenith's, for sky type 1–15, a direction at zenith angle
// `zenith` (radians, below π/2) at angular distance `to_sun` (radians) from a sun at zenith angle
// `sun_zenith`. Throws std::invalid_argument for a type outside 1–15.
double cie_sky_relative_luminance(int type, double zenith, double to_sun, double sun_zenith);

}  // namespace candela
