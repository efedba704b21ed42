// The scanline z-buffer rasterizer (000 §3; SPEC §9): one headless implementation serves the
// `raster` method, the hemicube's item buffers and the Gouraud display of radiosity solutions.
//
// Conventions (the same as Camera::generate_ray): pixel (x, y) covers [x, x+1) × [y, y+1) with
// y downward and is sampled at its centre (x + ½, y + ½); ndc (−1, 1) is the top-left corner
// of the image and (1, −1) the bottom-right. Triangles come in clip coordinates (OpenGL:
// inside when −w ≤ x, y, z ≤ w, w > 0).
//
// - Clipping: against the near plane (z ≥ −w) in clip space (a triangle crossing it becomes a
//   polygon of up to 4 vertices, fanned), the far plane likewise; triangles entirely outside
//   one of the six planes are culled without further work; x and y are cut by the scanline
//   bounds (no guard band needed in double precision).
// - Coverage: the top-left fill rule on pixel centres — a centre exactly on an edge belongs to
//   the triangle to its right (left edges inclusive, right edges exclusive) and a centre on a
//   horizontal edge to the triangle below it (top edges inclusive, bottom exclusive), so
//   triangles sharing an edge cover every pixel along it exactly once. Edge crossings at a
//   scanline are computed from the edge's endpoints in a canonical order, so both triangles of
//   a shared edge get bit-identical values.
// - Interpolation: perspective-correct — varyings/w and 1/w are interpolated linearly in screen
//   space and divided per pixel; the value at a scanline's first pixel comes from the edges,
//   then each next pixel adds a constant step (000 §3.2: I_p2 = I_p1 + ΔI·Δv). Depth is the
//   ndc z, interpolated linearly in screen space (exact for projections).
// - Depth test: a fragment is kept when its depth is strictly less than the buffer's (the
//   buffer starts at +∞); the fragment callback decides whether to write it.
//
// Implementation notes:
// - Screen position: x = (ndc_x + 1)/2·width, y = (1 − ndc_y)/2·height.
// - Canonical order: an edge is always walked from its upper endpoint (smaller screen y) to its
//   lower one; its crossing with the scanline through centres y_c is
//   x = x_upper + ((y_c − y_upper)·(x_lower − x_upper)) / (y_lower − y_upper), a single rounding
//   after an exact product for coordinates on a fine lattice, so that a centre exactly on an
//   edge is found exactly on it. Horizontal edges are never walked (no scanline lies strictly
//   inside their y range), so their order does not matter.
// - Clipping interpolates each new vertex from the edge's inside endpoint toward its outside
//   one, whichever way the polygon runs along it: the two triangles of a shared edge get the
//   same clipped vertex, bit for bit, and stay watertight after clipping.
// - Rows are evaluated directly from the edges (never stepped from row to row), so drawing a
//   region of full-width rows (a band) gives exactly the bytes of a full-image draw. A region
//   that starts inside a span starts its incremental walk there: coverage is the same as in a
//   full-image draw, depths and varyings agree to rounding (about 1e-15 relative).
// - Statistics: `culled` counts triangles with a non-finite clip coordinate, entirely outside
//   one of the six planes, or with nothing of positive area left on screen; `fragments`
//   counts covered pixel centres inside the region.
#pragma once

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

namespace candela {

// The most per-vertex values a triangle can carry (the dot-product mode needs two per light).
inline constexpr int kMaxVaryings = 64;

struct RasterVertex {
  Eigen::Vector4d clip;                       // clip coordinates
  std::array<double, kMaxVaryings> varyings;  // the first `varying_count` are interpolated
};

struct RasterStatistics {
  uint64_t triangles = 0;  // submitted
  uint64_t culled = 0;     // entirely outside a clip plane (or zero area on screen)
  uint64_t clipped = 0;    // cut by the near or far plane
  uint64_t fragments = 0;  // pixel centres covered (before the depth test)
  uint64_t written = 0;    // fragments that passed the depth test and were written
};

// What the fragment callback receives for one covered pixel that passed the depth test.
struct Fragment {
  int x = 0, y = 0;
  double depth = 0;        // ndc z in [−1, 1]
  const double* varyings;  // varying_count perspective-correct values
};

// The image-space box of a triangle given in clip coordinates (for binning triangles to tiles).
// `in_front` is false when a corner is behind the near plane: the clipped polygon may then
// reach anywhere on screen, and the box is unbounded.
struct ScreenBounds {
  double lower_x, upper_x, lower_y, upper_y;
  bool in_front;
};
inline ScreenBounds screen_bounds(const Eigen::Vector4d& a, const Eigen::Vector4d& b,
                                  const Eigen::Vector4d& c, int width, int height) {
  constexpr double kUnbounded = std::numeric_limits<double>::infinity();
  ScreenBounds box{kUnbounded, -kUnbounded, kUnbounded, -kUnbounded, true};
  for (const Eigen::Vector4d* corner : {&a, &b, &c}) {
    const Eigen::Vector4d& p = *corner;
    if (!(p.z() >= -p.w()) || !(p.w() > 0)) return {-kUnbounded, kUnbounded, -kUnbounded, kUnbounded, false};
    const double x = (p.x() / p.w() + 1) * 0.5 * width, y = (1 - p.y() / p.w()) * 0.5 * height;
    box.lower_x = std::min(box.lower_x, x), box.upper_x = std::max(box.upper_x, x);
    box.lower_y = std::min(box.lower_y, y), box.upper_y = std::max(box.upper_y, y);
  }
  return box;
}

class Rasterizer {
 public:
  // The image is width × height; `region` (default: all of it) limits drawing to the pixels
  // x0 ≤ x < x1, y0 ≤ y < y1 (tiles, --crop); the depth buffer covers only the region.
  // Throws std::invalid_argument for a width or height below 1.
  Rasterizer(int width, int height);
  // The same with a region from the start: a tile's rasterizer holds a tile-sized depth buffer
  // only (a full-image one per tile made large images quadratic). Throws like set_region.
  Rasterizer(int width, int height, int x0, int y0, int x1, int y1);
  // Throws std::invalid_argument unless 0 ≤ x0 ≤ x1 ≤ width and 0 ≤ y0 ≤ y1 ≤ height. The
  // depth buffer is resized and cleared.
  void set_region(int x0, int y0, int x1, int y1);
  void clear_depth();  // every depth to +∞

  // Draws one triangle. For every covered pixel centre in the region whose interpolated depth
  // is below the buffer's, calls shade(fragment) → bool; when it returns true the depth is
  // written (false leaves the buffer as it was, e.g. for a see-through test).
  // Throws std::invalid_argument unless 0 ≤ varying_count ≤ kMaxVaryings.
  template <typename Shade>
  void draw_triangle(const RasterVertex& a, const RasterVertex& b, const RasterVertex& c, int varying_count,
                     Shade&& shade);

  double depth_at(int x, int y) const;  // image coordinates inside the region (else std::out_of_range)
  const RasterStatistics& statistics() const { return statistics_; }
  void reset_statistics() { statistics_ = RasterStatistics{}; }
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  static constexpr int kMaxAttributes = 2 + kMaxVaryings;  // ndc depth, 1/w, varyings/w
  // A triangle clipped by the near and the far plane keeps at most five corners.
  static constexpr int kMaxPolygonCorners = 5;

  // A corner after the perspective division: its screen position and the values interpolated
  // linearly in screen space: [0] ndc depth, [1] 1/w, [2 + k] varying k / w (the last two
  // scaled alike per polygon, see normalize_inverse_w).
  struct ScreenVertex {
    double x, y;
    double attributes[kMaxAttributes];
  };
  struct ScreenPolygon {
    int count;
    ScreenVertex corners[kMaxPolygonCorners];
  };

  // One edge walked from its upper endpoint down, evaluated at scanline centres.
  class EdgeWalk {
   public:
    // upper.y ≤ lower.y; a horizontal edge (equal y) is built but never evaluated.
    EdgeWalk(const ScreenVertex& upper, const ScreenVertex& lower)
        : upper_(upper),
          lower_(lower),
          dx_(lower.x - upper.x),
          dy_(lower.y - upper.y),
          inverse_dy_(dy_ != 0 ? 1 / dy_ : 0) {}
    double x_at(double y) const { return upper_.x + ((y - upper_.y) * dx_) / dy_; }
    // The attributes at scanline y, linear along the edge (Gouraud's I_Q = u·I_B + (1−u)·I_A).
    void attributes_at(double y, int count, double* out) const {
      const double u = (y - upper_.y) * inverse_dy_;
      for (int k = 0; k < count; ++k)
        out[k] = upper_.attributes[k] + u * (lower_.attributes[k] - upper_.attributes[k]);
    }

   private:
    const ScreenVertex& upper_;
    const ScreenVertex& lower_;
    double dx_, dy_, inverse_dy_;
  };

  [[noreturn]] static void throw_bad_varying_count(int varying_count);
  // Counts the triangle, culls it, clips it against the near and far planes and projects what
  // is left; false when nothing is left to scan (counted as culled).
  bool prepare(const RasterVertex& a, const RasterVertex& b, const RasterVertex& c, int varying_count,
               ScreenPolygon& polygon);
  // Sutherland–Hodgman against the near and the far plane for a triangle that crosses one.
  bool clip_and_project(const RasterVertex& a, const RasterVertex& b, const RasterVertex& c,
                        int varying_count, ScreenPolygon& polygon);
  // The perspective division and the viewport mapping; false for a non-finite result or w ≤ 0.
  bool project(const double* clip, const double* varyings, int varying_count, ScreenVertex& out) const;
  // Scales 1/w and varying/w of every corner by the same factor, the largest 1/w becoming 1:
  // the perspective-correct quotient does not change, and corners with w near 0 (1/w up to
  // 1e308) no longer overflow the per-pixel steps.
  static void normalize_inverse_w(ScreenPolygon& polygon, int varying_count);
  // Scan-converts one triangle of the (fanned) polygon; false when it has no area on screen.
  template <typename Shade>
  bool scan_triangle(const ScreenVertex& a, const ScreenVertex& b, const ScreenVertex& c, int varying_count,
                     Shade& shade);

  // The smallest integer i with i + ½ ≥ v (the first pixel centre at or after v), clamped to
  // [low, high] (0 ≤ low ≤ high). Exact: the test i + ½ ≥ v decides, not the rounding of v − ½.
  static int first_centre_at_or_after(double v, int low, int high) {
    if (!(v > low + 0.5)) return low;
    if (v > high - 0.5) return high;
    // v − ½ > low ≥ 0 here, so truncation is the floor (cheaper than std::ceil without SSE4.1).
    int i = static_cast<int>(v - 0.5);
    while (i + 0.5 < v) ++i;
    while (i > low && i - 0.5 >= v) --i;
    return i;
  }

  int width_, height_;
  int x0_ = 0, y0_ = 0, x1_ = 0, y1_ = 0;
  std::vector<double> depth_;  // (x1 − x0)·(y1 − y0), row by row
  RasterStatistics statistics_;
};

template <typename Shade>
void Rasterizer::draw_triangle(const RasterVertex& a, const RasterVertex& b, const RasterVertex& c,
                               int varying_count, Shade&& shade) {
  // Checked here, inline, so that the compiler knows the loops below stay inside the arrays.
  if (varying_count < 0 || varying_count > kMaxVaryings) throw_bad_varying_count(varying_count);
  ScreenPolygon polygon;  // prepare fills the corners in use and only their live attributes
  if (!prepare(a, b, c, varying_count, polygon)) return;
  // The pixel centres within the polygon's screen bounds and the region: where there are none
  // (most triangles of a dense mesh fall between centres, and tiles miss most triangles) there
  // is nothing to scan, only the area to tell for the statistics.
  double lowest_x = polygon.corners[0].x, highest_x = lowest_x;
  double lowest_y = polygon.corners[0].y, highest_y = lowest_y;
  for (int i = 1; i < polygon.count; ++i) {
    lowest_x = std::min(lowest_x, polygon.corners[i].x);
    highest_x = std::max(highest_x, polygon.corners[i].x);
    lowest_y = std::min(lowest_y, polygon.corners[i].y);
    highest_y = std::max(highest_y, polygon.corners[i].y);
  }
  const bool no_centre =
      first_centre_at_or_after(lowest_x, x0_, x1_) == first_centre_at_or_after(highest_x, x0_, x1_) ||
      first_centre_at_or_after(lowest_y, y0_, y1_) == first_centre_at_or_after(highest_y, y0_, y1_);
  bool has_area = false;
  // The fan (0, k, k+1) of the convex clipped polygon (a single triangle when unclipped).
  for (int k = 1; k + 1 < polygon.count; ++k) {
    if (no_centre) {
      const ScreenVertex &p = polygon.corners[0], &q = polygon.corners[k], &r = polygon.corners[k + 1];
      const double twice_area = (q.x - p.x) * (r.y - p.y) - (r.x - p.x) * (q.y - p.y);
      has_area = has_area || twice_area != 0;
    } else {
      has_area = scan_triangle(polygon.corners[0], polygon.corners[k], polygon.corners[k + 1], varying_count,
                               shade) ||
                 has_area;
    }
  }
  if (!has_area) ++statistics_.culled;
}

template <typename Shade>
bool Rasterizer::scan_triangle(const ScreenVertex& a, const ScreenVertex& b, const ScreenVertex& c,
                               int varying_count, Shade& shade) {
  // Corners sorted by screen y (downward): top, middle, bottom.
  const ScreenVertex* top = &a;
  const ScreenVertex* middle = &b;
  const ScreenVertex* bottom = &c;
  if (middle->y < top->y) std::swap(top, middle);
  if (bottom->y < middle->y) std::swap(middle, bottom);
  if (middle->y < top->y) std::swap(top, middle);
  // The side of the long edge (top → bottom) the middle corner lies on; zero: no area.
  const double twice_area =
      (middle->x - top->x) * (bottom->y - top->y) - (bottom->x - top->x) * (middle->y - top->y);
  if (!(twice_area != 0)) return false;
  const bool middle_on_right = twice_area > 0;

  // Rows whose centre y_c satisfies top.y ≤ y_c < bottom.y (top edges in, bottom edges out);
  // above the middle corner's y the short edge is top → middle, from it on middle → bottom.
  const int row_begin = first_centre_at_or_after(top->y, y0_, y1_);
  const int row_split = first_centre_at_or_after(middle->y, y0_, y1_);
  const int row_end = first_centre_at_or_after(bottom->y, y0_, y1_);
  if (row_begin >= row_end) return true;

  const int attribute_count = varying_count == 0 ? 1 : 2 + varying_count;
  const EdgeWalk long_edge(*top, *bottom), upper_edge(*top, *middle), lower_edge(*middle, *bottom);
  double left_values[kMaxAttributes], right_values[kMaxAttributes];
  double values[kMaxAttributes], steps[kMaxAttributes];
  double varyings[kMaxVaryings];
  const int region_width = x1_ - x0_;
  uint64_t fragments = 0, written = 0;
  for (int row = row_begin; row < row_end; ++row) {
    const double y_centre = row + 0.5;
    const EdgeWalk& short_edge = row < row_split ? upper_edge : lower_edge;
    const EdgeWalk& left = middle_on_right ? long_edge : short_edge;
    const EdgeWalk& right = middle_on_right ? short_edge : long_edge;
    const double x_left = left.x_at(y_centre), x_right = right.x_at(y_centre);
    if (!(x_left < x_right)) continue;
    // Centres x_c with x_left ≤ x_c < x_right: left edges in, right edges out.
    const int column_begin = first_centre_at_or_after(x_left, x0_, x1_);
    const int column_end = first_centre_at_or_after(x_right, x0_, x1_);
    if (column_begin >= column_end) continue;

    // 000 §3.2: the values where the scanline meets the edges (I_Q, I_R), the constant
    // increment per pixel ΔI = (I_R − I_Q)/(x_R − x_Q), and the first pixel's value.
    left.attributes_at(y_centre, attribute_count, left_values);
    right.attributes_at(y_centre, attribute_count, right_values);
    const double inverse_span = 1 / (x_right - x_left);
    const double first_offset = column_begin + 0.5 - x_left;
    for (int k = 0; k < attribute_count; ++k) {
      steps[k] = (right_values[k] - left_values[k]) * inverse_span;
      values[k] = left_values[k] + steps[k] * first_offset;
    }

    double* depth_row = depth_.data() + static_cast<std::ptrdiff_t>(row - y0_) * region_width - x0_;
    fragments += static_cast<uint64_t>(column_end - column_begin);
    for (int x = column_begin; x < column_end; ++x) {
      if (values[0] < depth_row[x]) {
        if (varying_count > 0) {
          const double w = 1 / values[1];
          for (int k = 0; k < varying_count; ++k) varyings[k] = values[2 + k] * w;
        }
        Fragment fragment;
        fragment.x = x;
        fragment.y = row;
        fragment.depth = values[0];
        fragment.varyings = varyings;
        if (shade(static_cast<const Fragment&>(fragment))) {
          depth_row[x] = values[0];
          ++written;
        }
      }
      // I_p2 = I_p1 + ΔI·Δv with Δv one pixel.
      for (int k = 0; k < attribute_count; ++k) values[k] += steps[k];
    }
  }
  statistics_.fragments += fragments;
  statistics_.written += written;
  return true;
}

}  // namespace candela
