#pragma once

#include <limits>

namespace candela {

inline constexpr double kPi = 3.14159265358979323846;
inline constexpr double kInvPi = 1.0 / kPi;
inline constexpr double kInfinity = std::numeric_limits<double>::infinity();

inline constexpr double degrees_to_radians(double degrees) {
  return degrees * (kPi / 180.0);
}

}  // namespace candela
