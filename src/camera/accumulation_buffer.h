// Jittered samples for the views that draw a whole image at a time (the rasterizer: the raster
// method, radiosity's gouraud display), by the accumulation buffer (Haeberli & Akeley 1990, "The
// accumulation buffer: hardware support for high-quality rendering", SIGGRAPH '90): the
// image is drawn several times, each pass with the projection moved by a sub-pixel offset so that
// every pixel is sampled at (x + dx, y + dy) instead of its centre, and the passes' samples are
// splatted with the scene's filter into one film (camera/splat_film.h), as the ray tracers'
// samples are. A shifted projection moves the whole image: one offset serves every pixel of a
// pass (the ray tracers draw a random point per pixel), so a pixel's samples are stratified and
// jittered as theirs are, but every pixel has the same pattern (docs/antialiasing.md).
//   jittered  n² passes; pass k takes cell (k mod n, k div n) of the n × n sub-pixel cells, at a
//             point drawn at random within it for the pass: one random point in each cell.
//   corners, adaptive with jitter (a lattice jittered point by point cannot be drawn in passes):
//             the cells of a 2^L × 2^L grid (L = max_level, at least 1; corners: 1), taken in
//             a nested order — the first 4^l passes hold one point in each cell of the 2^l × 2^l
//             grid for every l ≤ L, each uniformly placed within it (base-4 digits of the pass
//             scrambled by the digits before them, then jittered). Every pixel takes the first 4
//             passes (one sample in each quadrant, the count of its corner rays). Their samples
//             over the image form one lattice of spacing about ½ (pixel (x, y)'s sample of
//             quadrant (i, j) is lattice point (2x + i, 2y + j)): a pixel takes all 4^L passes
//             (L ≥ 2; the count of the leaf squares the ray tracers stop at) where the contrast
//             (camera/contrast.h) of any square of four neighbouring lattice points reaching into
//             it exceeds aa.threshold — its own four samples, or those across its borders, so
//             that an edge passing between two pixels' samples refines both. A sample counts for
//             1/4 or 1/4^L of its pixel (its cell's area, as the ray tracers' leaf squares).
// Every offset is a pure function of the render's seed and the pass, and a pixel's refinement
// of its own samples, so neither the thread count nor a region (--crop, distributed tiles)
// changes a pixel: a region also samples the ring of pixels its filter reaches (and where the
// contrast test refines, one more, whose samples the test of the ring's pixels reads), and the
// film's sums are added in a fixed order (rows of one class mod 2·reach + 1 of the image in
// parallel).
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "camera/antialiasing.h"
#include "camera/film.h"
#include "camera/splat_film.h"

namespace candela {

// Whether the settings' samples lie off every grid (jittered; corners or adaptive with jitter),
// so that a rasterizing view draws them in passes.
bool drawn_in_passes(const AntialiasingSettings& settings);

// Where a pass samples every pixel: (x + dx, y + dy), dx, dy ∈ [0, 1).
struct PassOffset {
  double dx = 0.5, dy = 0.5;
  // What a rasterizer of a width × height image (pixel centres at x + ½, ndc x = (2X/width) − 1,
  // y upward) adds to ndc x and y so that its centres fall on the pass's points: in clip
  // coordinates x += w·ndc_shift_x, y += w·ndc_shift_y.
  double ndc_shift_x(int width) const { return 2 * (0.5 - dx) / width; }
  double ndc_shift_y(int height) const { return -2 * (0.5 - dy) / height; }
};

// The passes of settings for which drawn_in_passes holds, and where each samples.
class PassSchedule {
 public:
  PassSchedule(const AntialiasingSettings& settings, uint64_t seed);
  int first_passes() const { return first_; }  // drawn for every pixel
  int passes() const { return most_; }         // drawn for a pixel the contrast test refines
  PassOffset offset(int pass) const;

 private:
  int side_ = 1;    // cells per pixel side
  int levels_ = 0;  // the lattice modes: side = 2^levels, cells in the nested order
  int first_ = 1, most_ = 1;
  uint64_t stream_ = 0;  // the seed, mixed
};

// The pixels the passes draw for a width × height film at region: sampled_pixels, and where the
// contrast test refines, the ring around them (within the image).
PixelBox pixels_drawn_in_passes(const AntialiasingSettings& settings, const SamplingRegion& region, int width,
                                int height);

// Draws one pass: for every pixel (x, y) of `box` whose entry of `wanted` (box-sized, row by
// row) is nonzero, the view's value at (x + offset.dx, y + offset.dy) into the same entry of
// `values` (box-sized); the other entries are not read.
using PassDrawing = std::function<void(int pass, const PassOffset& offset, const PixelBox& box,
                                       const std::vector<uint8_t>& wanted, std::vector<Color>& values)>;

struct PassesResult {
  uint64_t samples = 0;         // values drawn (the ring around a region included)
  int passes = 0;               // passes drawn (fewer after Ctrl-C)
  int most_passes = 0;          // PassSchedule::passes()
  uint64_t refined_pixels = 0;  // of the region, that took every pass
};

// What accumulate_passes holds for the sampled pixels `box`: a pass's values, which pixels want
// it and their weights, the film's sums, and where the contrast test refines, the first four
// passes' values.
uint64_t accumulation_bytes(const AntialiasingSettings& settings, const PixelBox& box);

// Fills film — the pixels [region.x0, + film.width()) × [region.y0, + film.height()) of the
// image — from the passes of `settings` (drawn_in_passes), drawn over the pixels
// pixels_drawn_in_passes gives. After Ctrl-C (util/cancellation.h) no further pass
// is begun and the film holds the passes drawn whole (the one it cut short is left out). Throws
// std::invalid_argument for an unknown filter.
PassesResult accumulate_passes(const AntialiasingSettings& settings, uint64_t seed,
                               const SamplingRegion& region, const PassDrawing& draw, Film& film);

}  // namespace candela
