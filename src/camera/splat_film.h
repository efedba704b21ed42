// The film of a reconstruction filter (pbrt-v4's RGBFilm; SPEC §6 "real reconstruction filters
// that splat across pixels"): a rectangle of pixels, each holding Σ w·L and Σ w of the samples
// splatted into it. A sample lands in every pixel whose centre lies within the filter's support
// of it, with weight w = a·f(sample − centre) (a: the sample's own weight, a leaf square's area
// for the lattice modes); the pixel's value is Σ w·L / Σ w. Splats into different pixels may run
// concurrently; sample_image orders the tiles so that no two threads splat into one pixel and
// every pixel gets its sums in a fixed order.
#pragma once

#include <cstdlib>
#include <memory>
#include <type_traits>

#include "camera/pixel_filter.h"
#include "math/vector.h"

namespace candela {

// Pixels [x0, x1) × [y0, y1) of the image.
struct PixelBox {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  int width() const { return x1 - x0; }
  int height() const { return y1 - y0; }
  bool empty() const { return x1 <= x0 || y1 <= y0; }
  bool contains(int x, int y) const { return x >= x0 && x < x1 && y >= y0 && y < y1; }
  PixelBox grown(int by) const { return {x0 - by, y0 - by, x1 + by, y1 + by}; }
  PixelBox clipped(const PixelBox& to) const;
};

// How many pixels beyond its own a sample can reach with this filter: a sample at offset
// d ∈ [0, 1) in its pixel is (d − 0.5) + k from the centre k pixels away, inside the support
// [−r, r) while k < r + 0.5.
int filter_reach(const PixelFilter& filter);

class SplatFilm {
 public:
  explicit SplatFilm(const PixelBox& box = {});
  const PixelBox& box() const { return box_; }

  // A sample of pixel (px, py) at (px + dx, py + dy), dx, dy in [0, 1), with value L and own
  // weight a: w = a·f(dx − 0.5 + px − qx, dy − 0.5 + py − qy) into every pixel q of the box
  // with w ≠ 0. The offset to the sample's own pixel is dx − 0.5 exactly, so a box of radius 0.5
  // sums each pixel's own samples in the order they come. The box's pixel (px, py), when it holds
  // it, also keeps the plain a-weighted mean of its own samples (the fallback of resolve).
  void splat(const PixelFilter& filter, int px, int py, double dx, double dy, double a, const Color& value);

  // Σ w·L / Σ w at pixel (x, y) of the image; where the weights cancel (Σ w ≤ 1e-12: negative
  // lobes, a narrow Gaussian far from every sample) the plain mean of the pixel's own samples.
  Color resolve(int x, int y) const;

 private:
  struct Sums {
    Color weighted;  // Σ w·L
    double weight = 0;
    Color own;  // Σ a·L over the pixel's own samples
    double own_weight = 0;
  };
  Sums& at(int x, int y) { return pixels_[std::size_t(y - box_.y0) * box_.width() + (x - box_.x0)]; }
  const Sums& at(int x, int y) const {
    return pixels_[std::size_t(y - box_.y0) * box_.width() + (x - box_.x0)];
  }

  // Zeros from calloc: the operating system's fresh pages are zero already, and a vector's value
  // initialisation wrote the 64 bytes a pixel over again (16 MB for 500², some 3 % of a Whitted
  // render). Sums is an aggregate of doubles, whose zero bits are 0.
  struct Free {
    void operator()(Sums* sums) const noexcept { std::free(sums); }
  };
  static_assert(std::is_trivially_copyable_v<Sums> && std::is_trivially_destructible_v<Sums>);
  PixelBox box_;
  std::unique_ptr<Sums[], Free> pixels_;
};

}  // namespace candela
