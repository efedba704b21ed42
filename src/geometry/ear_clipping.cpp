#include "geometry/ear_clipping.h"

namespace candela {

namespace {

// Whether p lies in the counter-clockwise triangle a b c: with its boundary when closed,
// strictly inside otherwise.
bool in_triangle(const Vec2& p, const Vec2& a, const Vec2& b, const Vec2& c, bool closed) {
  const double ab = orientation(a, b, p), bc = orientation(b, c, p), ca = orientation(c, a, p);
  return closed ? (ab >= 0 && bc >= 0 && ca >= 0) : (ab > 0 && bc > 0 && ca > 0);
}

}  // namespace

std::vector<std::array<uint32_t, 3>> ear_clip(std::span<const Vec2> plane, std::span<const uint32_t> place) {
  std::vector<uint32_t> remaining(plane.size());
  for (std::size_t i = 0; i < remaining.size(); ++i) remaining[i] = static_cast<uint32_t>(i);
  const auto find_ear = [&](int pass) -> std::size_t {
    const std::size_t count = remaining.size();
    for (std::size_t i = 0; i < count; ++i) {
      const uint32_t previous = remaining[(i + count - 1) % count];
      const uint32_t current = remaining[i];
      const uint32_t next = remaining[(i + 1) % count];
      if (!(orientation(plane[previous], plane[current], plane[next]) > 0)) continue;
      bool holds_another = false;
      for (std::size_t j = 0; j < count && pass < 2 && !holds_another; ++j) {
        const uint32_t other = remaining[j];
        if (place[other] == place[previous] || place[other] == place[current] || place[other] == place[next])
          continue;
        holds_another = in_triangle(plane[other], plane[previous], plane[current], plane[next], pass == 0);
      }
      if (!holds_another) return i;
    }
    return count;
  };
  std::vector<std::array<uint32_t, 3>> triangles;
  while (remaining.size() >= 3) {
    const std::size_t count = remaining.size();
    std::size_t ear = count;
    for (int pass = 0; pass < 3 && ear == count; ++pass) ear = find_ear(pass);
    // No convex corner left: what remains spans no area (collinear corners).
    if (ear == count) break;
    triangles.push_back({remaining[(ear + count - 1) % count], remaining[ear], remaining[(ear + 1) % count]});
    remaining.erase(remaining.begin() + static_cast<std::ptrdiff_t>(ear));
  }
  return triangles;
}

}  // namespace candela
