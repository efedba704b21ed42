// Sites (seed 002 §4.1, SPEC §11): a point on a surface of the scene with the unit normal there,
// p = (ṗ, p⃗), and the site distance the meshless bases measure their support with.
#pragma once

#include <cmath>
#include <limits>

#include "math/vector.h"

namespace candela {

struct Site {
  Vec3 position;  // ṗ
  Vec3 normal;    // p⃗, unit, pointing out of the surface (toward where it was seen from)
};

// 002 eq. 4.1: ||p, q|| = |ṗ − q̇| / max(0, p⃗·q⃗) — the Euclidean distance stretched as the
// normals turn apart, infinite when they are 90° or more apart (and 0 only for the same point with
// normals less than 90° apart). Not a metric (no triangle inequality), never below |ṗ − q̇|.
inline double site_distance(const Site& p, const Site& q) {
  const double facing = std::max(0.0, dot(p.normal, q.normal));
  const double gap = length(p.position - q.position);
  if (facing <= 0) return std::numeric_limits<double>::infinity();
  return gap / facing;
}

}  // namespace candela
