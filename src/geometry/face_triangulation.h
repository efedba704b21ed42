// The triangles of one polygonal face of a mesh file (OBJ, PLY), shared by the readers so that a
// face is filled the same way whichever file it comes from, however many corners it has.
// - three corners: the triangle;
// - four: split along the shorter diagonal, in float, exactly as tinyobjloader's triangulation
//   did (so OBJ quads keep their triangles);
// - more: a polygon that is convex and planar (within 1e-5 of its size) is halved into
//   triangles that shrink towards its boundary (geometry/convex_triangulation.h, linear time: a
//   fan's slivers all overlap at one corner); any other one of at most kMaxNonConvexFaceCorners
//   corners is ear-clipped in the plane of its Newell normal (geometry/ear_clipping.h, quadratic
//   to cubic in the corners), and a larger one is refused. tinyobjloader's own ear clipping took
//   36 s for a convex face of 10⁵ corners (about an hour for 10⁶).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "math/vector.h"

namespace candela {

// The most corners of a face that is not convex and planar (see above).
inline constexpr std::size_t kMaxNonConvexFaceCorners = 1000;

// The triangles of the face with corners `p` as offsets into it (0 .. corners - 1), written to
// `triangles`; returns "" or, for a face it refuses, what is wrong (for the reader to locate).
// A face without area gives its degenerate fan (the mesh leaves such triangles out).
std::string triangulate_face(std::span<const Vec3> p, std::vector<std::array<uint32_t, 3>>& triangles);

}  // namespace candela
