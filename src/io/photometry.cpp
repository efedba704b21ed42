#include "io/photometry.h"

#include <algorithm>
#include <cmath>

#include "math/constants.h"

namespace candela {

namespace {

// The index i and weight t with angles[i] ≤ x ≤ angles[i + 1], x = lerp; false outside.
bool bracket(const std::vector<double>& angles, double x, std::size_t& i, double& t) {
  if (angles.size() == 1) {
    i = 0;
    t = 0;
    return x == angles[0];
  }
  if (!(x >= angles.front() && x <= angles.back())) return false;
  const auto upper = std::upper_bound(angles.begin(), angles.end(), x);
  i = std::min<std::size_t>(static_cast<std::size_t>(upper - angles.begin()), angles.size() - 1) - 1;
  t = (x - angles[i]) / (angles[i + 1] - angles[i]);
  return true;
}

}  // namespace

double Photometry::intensity(double vertical_degrees, double horizontal_degrees) const {
  if (vertical.empty() || horizontal.empty()) return 0;
  double h = horizontal_degrees;
  if (type == PhotometricType::c) {
    h = std::fmod(h, 360.0);
    if (h < 0) h += 360;
    const double h0 = horizontal.front(), h1 = horizontal.back();
    if (horizontal.size() == 1) {
      h = h0;
    } else if (h0 == 0 && h1 == 90) {  // quadrant symmetry
      if (h > 180) h = 360 - h;
      if (h > 90) h = 180 - h;
    } else if (h0 == 0 && h1 == 180) {  // bilateral about the 0–180 plane
      if (h > 180) h = 360 - h;
    } else if (h0 == 90 && h1 == 270) {  // bilateral about the 90–270 plane
      if (h < 90) h = 180 - h;
      if (h > 270) h = 540 - h;
    }
  } else if (horizontal.size() == 1 || (horizontal.front() == 0 && h < 0)) {
    h = horizontal.size() == 1 ? horizontal.front() : -h;  // mirrored about the 0 plane
  }
  std::size_t v_index, h_index;
  double tv, th;
  if (!bracket(vertical, vertical_degrees, v_index, tv)) return 0;
  const std::size_t nv = vertical.size();
  const auto at = [&](std::size_t hi, std::size_t vi) { return candela[hi * nv + vi]; };
  const auto along_vertical = [&](std::size_t hi) {
    return nv == 1 ? at(hi, 0) : (1 - tv) * at(hi, v_index) + tv * at(hi, v_index + 1);
  };
  if (bracket(horizontal, h, h_index, th))
    return horizontal.size() == 1 ? along_vertical(0)
                                  : (1 - th) * along_vertical(h_index) + th * along_vertical(h_index + 1);
  // Type C without symmetry whose last plane is short of 360°: between it and the first again.
  if (type == PhotometricType::c && horizontal.front() == 0 && h > horizontal.back()) {
    const double span = 360 - horizontal.back();
    const double t = span > 0 ? (h - horizontal.back()) / span : 0;
    return (1 - t) * along_vertical(horizontal.size() - 1) + t * along_vertical(0);
  }
  return 0;
}

double Photometry::flux() const {
  // Quarter-degree cells: the midpoint rule's error on a piecewise-bilinear table is far below
  // the files' own precision (three or four digits).
  constexpr int kPerDegree = 4;
  const double step = kPi / 180 / kPerDegree;
  double sum = 0;
  if (type == PhotometricType::c) {
    for (int i = 0; i < 180 * kPerDegree; ++i) {
      const double gamma = (i + 0.5) / kPerDegree;
      double ring = 0;
      for (int j = 0; j < 360 * kPerDegree; ++j) ring += intensity(gamma, (j + 0.5) / kPerDegree);
      sum += ring * std::sin(gamma * kPi / 180);
    }
  } else {
    // Types A and B: V and H from −90° to 90° span the sphere's front half; the back half is
    // (V, H ± 180°), which the tables describe only where H reaches it, so it counts as dark.
    for (int i = 0; i < 180 * kPerDegree; ++i) {
      const double v = -90 + (i + 0.5) / kPerDegree;
      double row = 0;
      for (int j = 0; j < 180 * kPerDegree; ++j) row += intensity(v, -90 + (j + 0.5) / kPerDegree);
      sum += row * std::cos(v * kPi / 180);
    }
  }
  return sum * step * step;
}

}  // namespace candela
