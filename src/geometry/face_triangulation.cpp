#include "geometry/face_triangulation.h"

#include <cmath>

#include "geometry/convex_triangulation.h"
#include "geometry/ear_clipping.h"
#include "math/bounds.h"
#include "math/constants.h"

namespace candela {

std::string triangulate_face(std::span<const Vec3> p, std::vector<std::array<uint32_t, 3>>& triangles) {
  triangles.clear();
  const std::size_t n = p.size();
  if (n == 3) {
    triangles.push_back({0, 1, 2});
    return "";
  }
  if (n == 4) {
    const auto squared = [&](int a, int b) {
      const float x = static_cast<float>(p[b].x) - static_cast<float>(p[a].x);
      const float y = static_cast<float>(p[b].y) - static_cast<float>(p[a].y);
      const float z = static_cast<float>(p[b].z) - static_cast<float>(p[a].z);
      return x * x + y * y + z * z;
    };
    if (squared(0, 2) < squared(1, 3)) {
      triangles.push_back({0, 1, 2});
      triangles.push_back({0, 2, 3});
    } else {
      triangles.push_back({0, 1, 3});
      triangles.push_back({1, 2, 3});
    }
    return "";
  }
  const auto fan = [&](const std::vector<uint32_t>& corners) {
    for (std::size_t k = 1; k + 1 < corners.size(); ++k)
      triangles.push_back({corners[0], corners[k], corners[k + 1]});
  };
  // Newell's vector, summed about the first corner (as geometry/polygon.cpp).
  Vec3 area_vector;
  Bounds3 box;
  for (std::size_t i = 0; i < n; ++i) box.extend(p[i]);
  for (std::size_t i = 1; i + 1 < n; ++i) area_vector += cross(p[i] - p[0], p[i + 1] - p[0]);
  const double size = length(box.diagonal());
  if (!(length(area_vector) > 0) || !(size > 0)) {
    std::vector<uint32_t> all(n);
    for (std::size_t i = 0; i < n; ++i) all[i] = static_cast<uint32_t>(i);
    fan(all);  // no area: every triangle is degenerate, and the loader skips them
    return "";
  }
  const Vec3 normal = normalize(area_vector);
  Vec3 u_axis;
  for (std::size_t i = 1; i < n && length_squared(u_axis) == 0; ++i) {
    u_axis = p[i] - p[0];
    u_axis -= normal * dot(u_axis, normal);
  }
  u_axis = normalize(u_axis);
  const Vec3 v_axis = cross(normal, u_axis);
  // The corners in the plane (counter-clockwise about the normal), repeated ones dropped.
  std::vector<Vec2> plane;
  std::vector<uint32_t> corner;
  bool planar = true;
  for (std::size_t i = 0; i < n; ++i) {
    if (p[i] == p[(i + 1) % n]) continue;
    const Vec3 offset = p[i] - p[0];
    planar = planar && std::fabs(dot(offset, normal)) <= 1e-5 * size;
    plane.push_back({dot(offset, u_axis), dot(offset, v_axis)});
    corner.push_back(static_cast<uint32_t>(i));
  }
  // Convex: no corner turns clockwise (beyond rounding) and the turns add up to one turn, not
  // two or more (a pentagram turns the same way at every corner).
  const std::size_t m = plane.size();
  bool convex = m >= 3;
  double turning = 0;
  for (std::size_t i = 0; i < m && convex; ++i) {
    const Vec2 &a = plane[(i + m - 1) % m], &b = plane[i], &c = plane[(i + 1) % m];
    const Vec2 in{b.x - a.x, b.y - a.y}, out{c.x - b.x, c.y - b.y};
    const double sine = in.x * out.y - in.y * out.x, cosine = in.x * out.x + in.y * out.y;
    // A corner may lie inside the chord of its neighbours by the rounding of the file's
    // coordinates (floats: a 10⁵-corner circle has bends of 6·10⁻⁵ rad, its vertices 6·10⁻⁸
    // off): up to 10⁻⁶ of the face's size is not a bend.
    const Vec2 chord{c.x - a.x, c.y - a.y};
    convex = sine >= -1e-6 * size * std::sqrt(chord.x * chord.x + chord.y * chord.y);
    turning += std::atan2(sine, cosine);
  }
  convex = convex && turning < 3 * kPi;
  if (convex && planar) {
    // Halved, not fanned: a fan's slivers all meet at one corner, and no accelerator separates
    // their boxes (geometry/convex_triangulation.h).
    for (const auto& [a, b, c] : triangulate_convex_polygon(static_cast<uint32_t>(m)))
      triangles.push_back({corner[a], corner[b], corner[c]});
    return "";
  }
  if (n > kMaxNonConvexFaceCorners)
    return "a face of " + std::to_string(n) + " corners that is not " + (convex ? "planar" : "convex") +
           ": such faces are triangulated (ear clipping) only up to " +
           std::to_string(kMaxNonConvexFaceCorners) + " corners; split it into smaller faces";
  std::vector<uint32_t> place(m);
  for (std::size_t i = 0; i < m; ++i) {
    place[i] = static_cast<uint32_t>(i);
    for (std::size_t k = 0; k < i; ++k)
      if (p[corner[k]] == p[corner[i]]) {
        place[i] = static_cast<uint32_t>(k);
        break;
      }
  }
  for (const auto& [a, b, c] : ear_clip(plane, place)) triangles.push_back({corner[a], corner[b], corner[c]});
  return "";
}

}  // namespace candela
