// Photometric units: how an amount of light given in lumens, candela, lux or
// candela per square metre becomes the renderer's radiometric RGB, and a colour given as a
// colour temperature.
//
// One conversion everywhere: the luminous efficacy of the renderer's white light, K = 179 lm/W
// (Radiance's convention: its `probe`-style lux are 179 × the Rec. 709 luminance of the RGB
// irradiance), so a photometric quantity Q_v of colour c becomes the radiometric RGB
// Q_v / K × c / Y(c), Y the Rec. 709 luminance (math/vector.h `luminance`): the colour carries no
// amount, only its chromaticity.
#pragma once

#include "math/vector.h"

namespace candela {

// lm/W: lumens per watt of the renderer's RGB (Radiance's 179, WHITE_EFFICACY).
inline constexpr double kLuminousEfficacy = 179.0;
// lm/W: the most any light has, monochromatic 555 nm where V(λ) = 1 (the candela's definition, SI
// 2019: 683 lm/W at 540 THz); what an --efficacy option is held to.
inline constexpr double kMaximumLuminousEfficacy = 683.0;

// c scaled to Rec. 709 luminance 1 (c must have a positive luminance).
inline Color unit_luminance(const Color& c) {
  return c / luminance(c);
}

// The linear Rec. 709 RGB of a blackbody at `kelvin` (Planck's law through the CIE 1931 2°
// colour-matching functions, in Wyman, Sloan and Shirley's 2013 multi-lobe fit; XYZ to linear
// sRGB/Rec. 709 with D65 white), negative channels (outside the gamut, below about 1,900 K)
// clipped, normalised to luminance 1. Kelvin from 1,000 to 40,000.
Color blackbody_color(double kelvin);

// A photometric amount of colour `color` (any luminance > 0) in the renderer's units.
inline Color radiometric(double photometric_amount, const Color& color) {
  return unit_luminance(color) * (photometric_amount / kLuminousEfficacy);
}

}  // namespace candela
