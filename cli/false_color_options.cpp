#include "false_color_options.h"

#include <fmt/format.h>

#include <cmath>

#include "commands.h"
#include "shading/photometric_units.h"

namespace candela::cli {

void check_false_color_options(const std::vector<double>& scale, bool logarithmic, int contours,
                               std::string_view unit) {
  if (!scale.empty()) {
    if (scale.size() != 2 || !std::isfinite(scale[0]) || !std::isfinite(scale[1]) || !(scale[0] < scale[1]))
      throw BadArgument(fmt::format("--scale expects LO,HI with LO < HI ({})", unit));
    if (logarithmic && !(scale[0] > 0)) throw BadArgument("--scale with --log needs LO > 0");
  }
  if (contours < 0 || contours > 256) throw BadArgument("--contours expects 0 to 256 steps");
}

void check_efficacy(double efficacy) {
  // 1e308 lm/W overflowed every lux value to inf. No light has more than 683 lm/W (the
  // luminous efficacy of 555 nm light, where V(λ) = 1: the definition of the candela).
  if (!(std::isfinite(efficacy) && efficacy > 0 && efficacy <= kMaximumLuminousEfficacy))
    throw BadArgument(
        fmt::format("--efficacy {}: must be a positive number of lm/W, at most {} (the luminous "
                    "efficacy of 555 nm light, the largest of any light)",
                    efficacy, kMaximumLuminousEfficacy));
}

}  // namespace candela::cli
