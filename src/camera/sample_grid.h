// The sample points of the anti-aliasing modes that lie on a regular grid, for the views that
// rasterize instead of tracing rays (raster, the radiosity gouraud display): they draw the grid at
// its resolution and hand its values to sample_image, which reconstructs them with the same
// filter as the ray tracers' samples (SPEC §6, §17: one camera sampling for every method).
//   none      the pixel centres: scale 1;
//   uniform   the n×n sub-pixel centres: the image at n× (sample i at x = (i + 0.5) / n);
//   corners   the pixel corners, and adaptive the lattice of spacing 2^-max_level pixel with
//             its borders (sample i at x = i / scale): the rasterized view has every lattice
//             point, and adaptive picks those its subdivision asks for.
// Jittered points and jittered lattices lie off every grid: no grid (a rasterizing view draws them
// in passes, camera/accumulation_buffer.h).
#pragma once

#include <cmath>
#include <cstdint>
#include <optional>

#include "camera/antialiasing.h"

namespace candela {

struct SampleGrid {
  int scale = 1;            // grid samples per pixel side
  bool on_lattice = false;  // samples at x = i / scale (corners, adaptive), else at (i + 0.5) / scale

  // The grid's samples over image pixels [x0, x1): indices [first(x0), end(x1)).
  int64_t first(int x0) const { return int64_t(x0) * scale; }
  int64_t end(int x1) const { return int64_t(x1) * scale + (on_lattice ? 1 : 0); }
  // The image position of sample i (one axis).
  double position(int64_t i) const { return (double(i) + (on_lattice ? 0.0 : 0.5)) / scale; }
  // The sample at image position x, which must be one of the grid's (one axis).
  int64_t index(double x) const {
    return static_cast<int64_t>(std::floor(x * scale + (on_lattice ? 0.5 : 0.0)));
  }
  // A rasterizer of end(image_size) pixels has its pixel centres on the samples when normalized
  // device coordinates are multiplied by this (the lattice reaches half a sample past the image
  // window on each side).
  double ndc_scale(int image_size) const {
    const double samples = double(image_size) * scale;
    return on_lattice ? samples / (samples + 1) : 1.0;
  }
};

// The grid of these settings' samples; none for jittered and for a jittered lattice.
std::optional<SampleGrid> sample_grid(const AntialiasingSettings& settings);

}  // namespace candela
