#pragma once

#include <limits>

namespace candela {

inline constexpr double kPi = 3.14159265358979323846;
inline constexpr double kInvPi = 1.0 / kPi;
inline constexpr double kInfinity = std::numeric_limits<double>::infinity();
// The largest magnitude a number of a scene may have (a coordinate, a size, a light's value):
// squares of larger values (distances, areas) leave double precision's range.
inline constexpr double kMaxSceneMagnitude = 1e16;

inline constexpr double degrees_to_radians(double degrees) {
  return degrees * (kPi / 180.0);
}

}  // namespace candela
