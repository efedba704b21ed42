// Small helpers the shapes share to sample points uniformly in area (SPEC §12, Shape::sample_area):
// choosing one part of a composite surface by its area and reusing the random number (the warps
// themselves are sampling/warps.h).
#pragma once

#include <algorithm>
#include <cmath>

#include "math/constants.h"
#include "math/vector.h"

namespace candela {

// The largest double below 1: remapped random numbers stay in [0, 1).
inline constexpr double kBelowOne = 0x1.fffffffffffffp-1;

// Picks part i of count with probability areas[i] / Σ areas by u, and rescales u to [0, 1)
// within the chosen part's interval (a part of area 0 is never picked). Returns count when the
// total area is 0.
template <int count>
int pick_by_area(const double (&areas)[count], double& u) {
  double total = 0;
  for (double a : areas) total += a;
  if (!(total > 0)) return count;
  double start = 0;
  int last = count;
  for (int i = 0; i < count; ++i) {
    if (!(areas[i] > 0)) continue;
    last = i;
    const double end = start + areas[i] / total;
    if (u < end) {
      u = std::clamp((u - start) / (end - start), 0.0, kBelowOne);
      return i;
    }
    start = end;
  }
  // Rounding left u past the last boundary: the last part of positive area.
  u = kBelowOne;
  return last;
}

}  // namespace candela
