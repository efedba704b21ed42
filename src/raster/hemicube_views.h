// The five views of a hemicube (000 §6.4; Cohen and Greenberg 1985, "The Hemi-Cube: A Radiosity
// Solution for Complex Environments"): a cube of edge 2 centred on a point of a surface, its
// top face parallel to the surface. Each face is a 90° square frustum from the centre; an item
// buffer drawn with its matrix tells which patch is seen through every cell.
//
// The frame at the point: n = normalize(normal); t = tangent_hint made perpendicular to n and
// normalised (any perpendicular when the hint is zero, not finite or parallel to n);
// b = n × t, so that (t, b, n) is right-handed. The faces, named after the edges of the top
// face's image that they continue (the unfolded cross of Cohen and Greenberg's Figure 4):
//
//   face    looks along   image right   image up (row 0 side)
//   top     +n            +b            +t
//   front   +t            −b            +n
//   back    −t            +b            +n
//   right   +b            +t            +n
//   left    −b            −t            +n
//
// (image right = view direction × image up, as Camera::generate_ray's X = G × U.) So the top
// face's image has the front face beyond its top row, the back face beyond its bottom row, the
// right face beyond its right column and the left face beyond its left column.
//
// Above the surface: every side face looks along the surface with its image up along n, so the
// directions above the surface (d·n > 0) are exactly those seen at ndc y > 0 — the UPPER half of
// the image in rows: pixel centres with y + ½ < height/2, i.e. rows 0 … height/2 − 1 for an even
// height (ItemBuffer::set_region(0, 0, width, height / 2) draws only those). Centres at
// y + ½ = height/2 (the middle row of an odd height) look exactly along the surface. The full
// square frustum is returned; the caller uses only the upper half of a side face.
#pragma once

#include <Eigen/Dense>
#include <array>

#include "math/vector.h"

namespace candela {

enum class HemicubeFace { top, front, back, left, right };

inline constexpr std::array<HemicubeFace, 5> kHemicubeFaces = {
    HemicubeFace::top, HemicubeFace::front, HemicubeFace::back, HemicubeFace::left, HemicubeFace::right};

// The unit axes of one face's view (see the table above).
struct HemicubeFaceAxes {
  Vec3 forward;  // the direction the face looks along (its centre)
  Vec3 right;    // ndc +x, image columns to the right
  Vec3 up;       // ndc +y, image rows upward (toward row 0)
};

// Throws std::invalid_argument for a zero or non-finite normal.
HemicubeFaceAxes hemicube_face_axes(const Vec3& normal, const Vec3& tangent_hint, HemicubeFace face);

// World → OpenGL clip coordinates of one face: a 90° square frustum from center along the face's
// direction (ndc x = right·d / forward·d, ndc y = up·d / forward·d for d = p − center), depth
// −1 at forward·d = near and +1 at far. Use it with a square image (width = height). Throws
// std::invalid_argument for a bad normal or unless 0 < near < far (finite).
Eigen::Matrix4d hemicube_view_projection(const Vec3& center, const Vec3& normal, const Vec3& tangent_hint,
                                         HemicubeFace face, double near, double far);

}  // namespace candela
