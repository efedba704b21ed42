#include "camera/splat_film.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <new>

namespace candela {

PixelBox PixelBox::clipped(const PixelBox& to) const {
  PixelBox box{std::max(x0, to.x0), std::max(y0, to.y0), std::min(x1, to.x1), std::min(y1, to.y1)};
  if (box.empty()) return {};
  return box;
}

int filter_reach(const PixelFilter& filter) {
  return std::max(0, static_cast<int>(std::ceil(filter.radius() + 0.5)) - 1);
}

SplatFilm::SplatFilm(const PixelBox& box) : box_(box.empty() ? PixelBox{} : box) {
  const std::size_t count = std::max<std::size_t>(std::size_t(box_.width()) * box_.height(), 1);
  pixels_.reset(static_cast<Sums*>(std::calloc(count, sizeof(Sums))));
  if (!pixels_) throw std::bad_alloc();
}

void SplatFilm::splat(const PixelFilter& filter, int px, int py, double dx, double dy, double a,
                      const Color& value) {
  if (box_.contains(px, py)) {
    Sums& own = at(px, py);
    own.own += value * a;
    own.own_weight += a;
  }
  const int reach = filter_reach(filter);
  const int qx0 = std::max(px - reach, box_.x0), qx1 = std::min(px + reach + 1, box_.x1);
  const int qy0 = std::max(py - reach, box_.y0), qy1 = std::min(py + reach + 1, box_.y1);
  if (qx0 >= qx1 || qy0 >= qy1) return;
  // At most 33 pixels a side (radius ≤ 16, pixel_filter.cpp); only the entries of [q0, q1) are
  // written and read: not zero-filled, which took 640 bytes of stores a sample (about 5 % of a
  // Whitted render's time with the box filter, whose reach is the pixel itself).
  std::array<double, 40> wx, wy;
  const double ox = dx - 0.5, oy = dy - 0.5;
  for (int qx = qx0; qx < qx1; ++qx)
    wx[static_cast<std::size_t>(qx - qx0)] = filter.evaluate_1d(ox + (px - qx));
  for (int qy = qy0; qy < qy1; ++qy)
    wy[static_cast<std::size_t>(qy - qy0)] = filter.evaluate_1d(oy + (py - qy));
  for (int qy = qy0; qy < qy1; ++qy) {
    const double weight_y = wy[static_cast<std::size_t>(qy - qy0)];
    if (weight_y == 0) continue;
    for (int qx = qx0; qx < qx1; ++qx) {
      const double weight = wx[static_cast<std::size_t>(qx - qx0)] * weight_y * a;
      if (weight == 0) continue;
      Sums& sums = at(qx, qy);
      sums.weighted += value * weight;
      sums.weight += weight;
    }
  }
}

Color SplatFilm::resolve(int x, int y) const {
  const Sums& sums = at(x, y);
  if (sums.weight > 1e-12) return sums.weighted / sums.weight;
  return sums.own_weight > 0 ? sums.own / sums.own_weight : Color();
}

}  // namespace candela
