// pbrt-v4's named spectra (its file-format documentation, "Spectra") as the RGB values Candela
// reads: a metal's complex index of refraction η + iκ per sRGB channel, a glass's index.
#pragma once

#include <array>
#include <optional>
#include <string>

namespace candela {

using PbrtRgb = std::array<double, 3>;

// "metal-Cu-eta", "metal-Cu-k" and the same of Au, Ag and Al: the measured spectra integrated
// against the sRGB primaries, as the RGB conductor tables renderers publish (Mitsuba's and
// pbrt-v3 scenes' Cu, Au, Ag, Al). Nothing for another name.
std::optional<PbrtRgb> pbrt_metal_spectrum(const std::string& name);

// "glass-BK7", "glass-BAF10", "glass-FK51A", "glass-LASF9", "glass-F5", "-F10", "-F11": the
// glass's index at the helium d line (587.6 nm), Schott's catalogue n_d. Nothing for another name.
std::optional<double> pbrt_glass_index(const std::string& name);

}  // namespace candela
