#include "raster/rasterizer.h"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>

namespace candela {

namespace {

// Outcodes: one bit per clip plane a corner lies outside of.
enum OutsideBit : unsigned {
  kLeft = 1u << 0,    // x < −w
  kRight = 1u << 1,   // x > w
  kBottom = 1u << 2,  // y < −w
  kTop = 1u << 3,     // y > w
  kNear = 1u << 4,    // z < −w
  kFar = 1u << 5,     // z > w
};

unsigned outside_bits(const Eigen::Vector4d& clip) {
  const double w = clip.w();
  unsigned bits = 0;
  if (w + clip.x() < 0) bits |= kLeft;
  if (w - clip.x() < 0) bits |= kRight;
  if (w + clip.y() < 0) bits |= kBottom;
  if (w - clip.y() < 0) bits |= kTop;
  if (w + clip.z() < 0) bits |= kNear;
  if (w - clip.z() < 0) bits |= kFar;
  return bits;
}

// A polygon corner in clip space while Sutherland–Hodgman runs.
struct ClipVertex {
  double clip[4];
  double varyings[kMaxVaryings];
};

// Signed distance to the near (z = −w) or the far (z = w) plane: ≥ 0 inside.
double plane_distance(const ClipVertex& v, bool far_plane) {
  return far_plane ? v.clip[3] - v.clip[2] : v.clip[3] + v.clip[2];
}

void copy_vertex(const ClipVertex& from, int varying_count, ClipVertex& to) {
  std::copy(from.clip, from.clip + 4, to.clip);
  std::copy(from.varyings, from.varyings + varying_count, to.varyings);
}

// The point where the edge from `inside` to `outside` meets the plane, always interpolated from
// the inside endpoint: the same edge of two triangles gives the same vertex, bit for bit.
void intersect_edge(const ClipVertex& inside, double inside_distance, const ClipVertex& outside,
                    double outside_distance, int varying_count, ClipVertex& out) {
  const double t = inside_distance / (inside_distance - outside_distance);
  for (int i = 0; i < 4; ++i) out.clip[i] = inside.clip[i] + t * (outside.clip[i] - inside.clip[i]);
  for (int k = 0; k < varying_count; ++k)
    out.varyings[k] = inside.varyings[k] + t * (outside.varyings[k] - inside.varyings[k]);
}

// Sutherland–Hodgman (1974) against one plane: keeps the part of the convex polygon with
// distance ≥ 0. A convex polygon of n corners gives at most n + 1.
int clip_against_plane(const ClipVertex* in, int count, bool far_plane, int varying_count, ClipVertex* out) {
  int written = 0;
  for (int i = 0; i < count; ++i) {
    const ClipVertex& start = in[i];
    const ClipVertex& end = in[(i + 1) % count];
    const double start_distance = plane_distance(start, far_plane);
    const double end_distance = plane_distance(end, far_plane);
    const bool start_inside = start_distance >= 0, end_inside = end_distance >= 0;
    if (start_inside) copy_vertex(start, varying_count, out[written++]);
    if (start_inside && !end_inside)
      intersect_edge(start, start_distance, end, end_distance, varying_count, out[written++]);
    else if (!start_inside && end_inside)
      intersect_edge(end, end_distance, start, start_distance, varying_count, out[written++]);
  }
  return written;
}

}  // namespace

Rasterizer::Rasterizer(int width, int height) : Rasterizer(width, height, 0, 0, width, height) {}

Rasterizer::Rasterizer(int width, int height, int x0, int y0, int x1, int y1)
    : width_(width), height_(height) {
  if (width < 1 || height < 1)
    throw std::invalid_argument("rasterizer: the image must be at least 1 x 1 pixels, not " +
                                std::to_string(width) + " x " + std::to_string(height));
  set_region(x0, y0, x1, y1);
}

void Rasterizer::set_region(int x0, int y0, int x1, int y1) {
  if (!(0 <= x0 && x0 <= x1 && x1 <= width_ && 0 <= y0 && y0 <= y1 && y1 <= height_))
    throw std::invalid_argument("rasterizer: region [" + std::to_string(x0) + ", " + std::to_string(x1) +
                                ") x [" + std::to_string(y0) + ", " + std::to_string(y1) +
                                ") is not inside the " + std::to_string(width_) + " x " +
                                std::to_string(height_) + " image");
  x0_ = x0;
  y0_ = y0;
  x1_ = x1;
  y1_ = y1;
  depth_.assign(static_cast<std::size_t>(x1 - x0) * static_cast<std::size_t>(y1 - y0),
                std::numeric_limits<double>::infinity());
}

void Rasterizer::clear_depth() {
  std::fill(depth_.begin(), depth_.end(), std::numeric_limits<double>::infinity());
}

double Rasterizer::depth_at(int x, int y) const {
  if (x < x0_ || x >= x1_ || y < y0_ || y >= y1_)
    throw std::out_of_range("rasterizer: pixel (" + std::to_string(x) + ", " + std::to_string(y) +
                            ") is outside the region");
  return depth_[static_cast<std::size_t>(y - y0_) * static_cast<std::size_t>(x1_ - x0_) +
                static_cast<std::size_t>(x - x0_)];
}

void Rasterizer::throw_bad_varying_count(int varying_count) {
  throw std::invalid_argument("rasterizer: varying_count " + std::to_string(varying_count) +
                              " is outside [0, " + std::to_string(kMaxVaryings) + "]");
}

bool Rasterizer::project(const double* clip, const double* varyings, int varying_count,
                         ScreenVertex& out) const {
  const double w = clip[3];
  if (!(w > 0)) return false;
  const double inverse_w = 1 / w;
  // ndc, then x = (ndc_x + 1)/2·width, y = (1 − ndc_y)/2·height.
  out.x = (clip[0] * inverse_w + 1) * (0.5 * width_);
  out.y = (1 - clip[1] * inverse_w) * (0.5 * height_);
  out.attributes[0] = clip[2] * inverse_w;
  out.attributes[1] = inverse_w;
  for (int k = 0; k < varying_count; ++k) out.attributes[2 + k] = varyings[k] * inverse_w;
  return std::isfinite(out.x) && std::isfinite(out.y) && std::isfinite(out.attributes[0]) &&
         std::isfinite(inverse_w);
}

bool Rasterizer::prepare(const RasterVertex& a, const RasterVertex& b, const RasterVertex& c,
                         int varying_count, ScreenPolygon& polygon) {
  ++statistics_.triangles;
  // A corner that is not finite cannot be placed: the triangle is skipped.
  if (!a.clip.allFinite() || !b.clip.allFinite() || !c.clip.allFinite()) {
    ++statistics_.culled;
    return false;
  }
  const unsigned bits_a = outside_bits(a.clip), bits_b = outside_bits(b.clip), bits_c = outside_bits(c.clip);
  if ((bits_a & bits_b & bits_c) != 0) {  // every corner outside the same plane
    ++statistics_.culled;
    return false;
  }
  if (((bits_a | bits_b | bits_c) & (kNear | kFar)) != 0) {
    ++statistics_.clipped;
    if (clip_and_project(a, b, c, varying_count, polygon)) return true;
    ++statistics_.culled;
    return false;
  }
  // Inside both depth planes: w ≥ |z| ≥ 0 at every corner, projected as they are.
  polygon.count = 3;
  if (project(a.clip.data(), a.varyings.data(), varying_count, polygon.corners[0]) &&
      project(b.clip.data(), b.varyings.data(), varying_count, polygon.corners[1]) &&
      project(c.clip.data(), c.varyings.data(), varying_count, polygon.corners[2])) {
    normalize_inverse_w(polygon, varying_count);
    return true;
  }
  ++statistics_.culled;  // w = 0 on both depth planes at once: a degenerate projection
  return false;
}

void Rasterizer::normalize_inverse_w(ScreenPolygon& polygon, int varying_count) {
  if (varying_count == 0) return;  // 1/w is not interpolated then
  double largest = 0;
  for (int i = 0; i < polygon.count; ++i) largest = std::max(largest, polygon.corners[i].attributes[1]);
  const double scale = 1 / largest;
  if (scale == 1 || !std::isfinite(scale)) return;
  for (int i = 0; i < polygon.count; ++i)
    for (int k = 1; k < 2 + varying_count; ++k) polygon.corners[i].attributes[k] *= scale;
}

bool Rasterizer::clip_and_project(const RasterVertex& a, const RasterVertex& b, const RasterVertex& c,
                                  int varying_count, ScreenPolygon& polygon) {
  ClipVertex first[kMaxPolygonCorners], second[kMaxPolygonCorners];
  const RasterVertex* corners[3] = {&a, &b, &c};
  for (int i = 0; i < 3; ++i) {
    std::copy(corners[i]->clip.data(), corners[i]->clip.data() + 4, first[i].clip);
    std::copy(corners[i]->varyings.data(), corners[i]->varyings.data() + varying_count, first[i].varyings);
  }
  // Near plane: 3 corners → at most 4; far plane: → at most 5.
  const int after_near = clip_against_plane(first, 3, /*far_plane=*/false, varying_count, second);
  const int after_far = clip_against_plane(second, after_near, /*far_plane=*/true, varying_count, first);
  if (after_far < 3) return false;
  polygon.count = after_far;
  for (int i = 0; i < after_far; ++i)
    if (!project(first[i].clip, first[i].varyings, varying_count, polygon.corners[i])) return false;
  normalize_inverse_w(polygon, varying_count);
  return true;
}

}  // namespace candela
