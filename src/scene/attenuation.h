// Distance attenuation f_at of a local light (SPEC §7).
#pragma once

#include <algorithm>

#include "math/constants.h"

namespace candela {

struct Attenuation {
  enum class Mode {
    none,            // f = 1
    inverse_square,  // f = 1 / (4π d²)            000 §2.6
    linear,          // f = 1 / (d + d0)           000 eq. 2-5
    polynomial,      // f = min(1, 1 / (c + l d + q d²))   001's f_at
  };
  Mode mode = Mode::none;
  double d0 = 1;                                               // linear
  double constant = 1, linear_coefficient = 0, quadratic = 0;  // polynomial

  double factor(double distance) const {
    switch (mode) {
      case Mode::none:
        return 1.0;
      case Mode::inverse_square:
        return 1.0 / (4 * kPi * distance * distance);
      case Mode::linear:
        return 1.0 / (distance + d0);
      case Mode::polynomial: {
        const double denominator = constant + linear_coefficient * distance + quadratic * distance * distance;
        return denominator > 1 ? 1.0 / denominator : 1.0;
      }
    }
    return 1.0;
  }
};

}  // namespace candela
