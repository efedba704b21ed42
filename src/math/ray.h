// 000 eq. 5-1: r(t) = O + D t. Hits are accepted for t_min < t < t_max.
#pragma once

#include "math/constants.h"
#include "math/vector.h"

namespace candela {

struct Ray {
  Vec3 origin;
  Vec3 direction;  // unit length for every ray a method creates
  double t_min = 0.0;
  double t_max = kInfinity;

  Vec3 at(double t) const { return origin + direction * t; }
};

}  // namespace candela
