// The checks of the options that pictures in false colour and photometric units share: probe
// --image, falsecolor, compare --luminance (BadArgument, exit code 2, before any work).
#pragma once

#include <string_view>
#include <vector>

namespace candela::cli {

// --scale LO,HI (empty: none given; else two finite values LO < HI, LO > 0 with --log) in `unit`,
// and --contours 0 to 256.
void check_false_color_options(const std::vector<double>& scale, bool logarithmic, int contours,
                               std::string_view unit);

// --efficacy: a positive number of lm/W.
void check_efficacy(double efficacy);

}  // namespace candela::cli
