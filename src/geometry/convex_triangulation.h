// Triangles of a convex polygon that a ray structure can separate, however many corners. A
// fan from one corner makes every triangle a sliver that starts at that corner, so the boxes of
// all of them overlap there and cover most of the polygon: a BVH over the fan of a 10⁵-corner
// disc visits about half its 10⁵ leaves per ray (0.007 Mrays/s). Halving instead — one triangle
// over three corners a third of the way round apart, then in each arc the triangle from its ends
// to its middle corner, and so on — gives triangles that shrink towards the boundary, log₂
// corners levels deep; a point of that disc lies in at most 13 of the 99,998 triangles' boxes.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

namespace candela {

// The corners − 2 triangles of a convex polygon of `corners` corners (at least 3), as offsets
// into its corners, in the polygon's own order (a polygon counter-clockwise about its normal gives
// counter-clockwise triangles); linear time. Three corners give {0, 1, 2}.
std::vector<std::array<uint32_t, 3>> triangulate_convex_polygon(uint32_t corners);

}  // namespace candela
