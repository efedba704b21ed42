// A test image with one straight edge and its exact answer: white where n·(p − p0) > 0, black
// elsewhere, through p0 near the centre of a width × height image at `degrees`, and the exact
// white area of each pixel (the anti-aliasing tests of camera/antialiasing_test.cpp and
// camera/accumulation_buffer_test.cpp measure their pixels against it).
#pragma once

#include <cmath>
#include <numbers>
#include <utility>
#include <vector>

#include "math/vector.h"

namespace candela::testing {

struct HalfPlane {
  double nx, ny, d;
  HalfPlane(double degrees, int width, int height) {
    const double a = degrees * std::numbers::pi / 180;
    nx = -std::sin(a);
    ny = std::cos(a);
    d = nx * (width / 2.0 + 0.31) + ny * (height / 2.0 + 0.17);
  }
  double side(double x, double y) const { return nx * x + ny * y - d; }
  Color operator()(double x, double y) const { return Color(side(x, y) > 0 ? 1.0 : 0.0); }
  // The exact white area of pixel (px, py): the unit square clipped by the half-plane.
  double covered(int px, int py) const {
    std::vector<std::pair<double, double>> polygon{{px, py}, {px + 1, py}, {px + 1, py + 1}, {px, py + 1}};
    std::vector<std::pair<double, double>> clipped;
    for (std::size_t i = 0; i < polygon.size(); ++i) {
      const auto a = polygon[i], b = polygon[(i + 1) % polygon.size()];
      const double sa = side(a.first, a.second), sb = side(b.first, b.second);
      if (sa > 0) clipped.push_back(a);
      if ((sa > 0) != (sb > 0)) {
        const double t = sa / (sa - sb);
        clipped.emplace_back(a.first + t * (b.first - a.first), a.second + t * (b.second - a.second));
      }
    }
    double area = 0;
    for (std::size_t i = 0; i < clipped.size(); ++i) {
      const auto a = clipped[i], b = clipped[(i + 1) % clipped.size()];
      area += a.first * b.second - b.first * a.second;
    }
    return std::fabs(area) / 2;
  }
};

}  // namespace candela::testing
