#include "false_color_options.h"

#include <fmt/format.h>

#include <cmath>

#include "commands.h"

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
  if (!(std::isfinite(efficacy) && efficacy > 0))
    throw BadArgument("--efficacy must be a positive number (lm/W)");
}

}  // namespace candela::cli
