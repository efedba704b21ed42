// Combining sampling strategies (Veach 1997, ch. 9): the weight of a sample drawn by a strategy of
// density a when another strategy could have drawn it with density b.
#pragma once

namespace candela {

// The power heuristic with β = 2 (one sample from each strategy): a² / (a² + b²), 0 when both are 0.
inline double power_heuristic(double a, double b) {
  const double a2 = a * a, b2 = b * b;
  return a2 + b2 > 0 ? a2 / (a2 + b2) : 0.0;
}

}  // namespace candela
