// How a scene file gives an amount of light in photometric units (the
// conversion is shading/photometric_units.h): which one of a plugin's alternative amount keys
// it uses, and the colour of a photometric amount.
#pragma once

#include <initializer_list>
#include <string>
#include <string_view>

#include "io/json_node.h"
#include "math/vector.h"

namespace candela {

// Which of the keys (the radiometric one first, then the photometric ones) the node gives; at
// most one (else InputError at the second). The first when none is given (its default applies).
std::string amount_key(const JsonNode& node, std::initializer_list<const char*> keys);

// The colour of a photometric amount: color_key (RGB; only its chromaticity counts: it is scaled
// to luminance 1) or temperature_key (a blackbody, kelvin, 1,000 to 40,000); `fallback` (white)
// when neither is given.
Color read_photometric_color(const JsonNode& node, std::string_view color_key = "color",
                             std::string_view temperature_key = "temperature",
                             const Color& fallback = Color(1));

}  // namespace candela
