// Ear clipping of a simple polygon in its plane (Meisters 1975: every simple polygon of more than
// three vertices has two ears), shared by the polygon shape's tessellation and the OBJ reader's
// non-convex faces, so that both fill a polygon the same way.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "math/vector.h"

namespace candela {

// Twice the signed area of the triangle a b c in the plane: > 0 when counter-clockwise.
inline double orientation(const Vec2& a, const Vec2& b, const Vec2& c) {
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

// The triangles (indices into the corners, counter-clockwise) of the polygon whose corners are
// `plane` (counter-clockwise, no two consecutive ones equal); `place[i] == place[j]` says that
// corners i and j are at the same point (a polygon touching itself), so neither counts as lying
// inside an ear of the other. An ear is a strictly convex corner whose triangle with its
// neighbours holds no other corner. The first pass also refuses corners on the triangle's
// boundary, which keeps a collinear corner on the new diagonal from being left out as a
// T-junction; the second accepts them; the last takes any convex corner, so that rounding on a
// nearly degenerate polygon cannot stall the loop. At most corners - 2 triangles (fewer when
// what remains spans no area); O(corners³) at worst, so callers bound the corner count.
std::vector<std::array<uint32_t, 3>> ear_clip(std::span<const Vec2> plane, std::span<const uint32_t> place);

}  // namespace candela
