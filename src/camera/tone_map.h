// From linear film values to display values (000 §2.8–2.9, SPEC §6).
#pragma once

#include <cstdint>
#include <string_view>
#include <vector>

#include "camera/film.h"
#include "math/srgb.h"
#include "util/enum_names.h"

namespace candela {

enum class OutOfRange {
  clamp,      // per channel to [0, 1] (local)
  scale,      // the whole image divided by its largest value when that exceeds 1 (global)
  normalize,  // per pixel, divided by its largest channel when that exceeds 1 (keeps hue)
};

inline constexpr auto kOutOfRangeNames = enum_names<OutOfRange>(
    {{OutOfRange::clamp, "clamp"}, {OutOfRange::scale, "scale"}, {OutOfRange::normalize, "normalize"}});

struct DisplaySettings {
  OutOfRange out_of_range = OutOfRange::clamp;
  double exposure = 0;  // stops: values are multiplied by 2^exposure first
  bool srgb = true;     // encode with the sRGB transfer curve, else linear 8-bit
};

// Exposure only: what EXR and PFM store.
std::vector<Color> expose(const Film& film, double exposure);
// Exposure, out-of-range handling, then sRGB or linear quantisation: RGB8 rows, top first.
std::vector<uint8_t> to_display(const Film& film, const DisplaySettings& settings);

}  // namespace candela
