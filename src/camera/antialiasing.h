// Anti-aliasing (SPEC §6; 000 §5.8; 001): where each pixel's primary rays go, and how the
// samples are reconstructed into pixels.
//   none      one ray through the pixel centre;
//   uniform   n×n sub-pixel centres;  jittered: one random point in each of the n×n sub-cells
//             (the pixel's own random stream);
//   corners   rays through the pixel corners, shared with the neighbours: (W+1)(H+1) rays; each
//             pixel's square is one leaf, the mean of its four corners;
//   adaptive  corner rays; a square splits into four while the contrast
//             C = (Imax − Imin) / (Imax + Imin) of any channel over its four corners exceeds that
//             channel's threshold and its level is below max_level; every sample is traced once
//             and reused within and across pixels; each leaf square is the mean of its four
//             corners (001's worked example).
// Reconstruction, every mode alike (pbrt-v4's film, camera/splat_film.h): a point sample, or a
// leaf square as one sample at its centre with its area as weight, is splatted with the pixel
// filter into every pixel whose centre lies within the filter's radius; a pixel is Σ w·L / Σ w.
// With the box of radius 0.5 that is each pixel's own samples' mean (for a lattice mode the
// area-weighted mean of its leaves, 000 §5.8.2); a wider filter spreads a sample over its
// neighbours. The image is cut into tiles of tile_size pixels, aligned on the image's own grid;
// a tile splats its pixels' samples into the film, reaching the ring of pixels around it that
// the filter reaches. Tiles far enough apart to share no pixel run in parallel, in classes taken
// one after the other in a fixed order, so neither the thread count nor how a caller cuts the
// image into regions (distributed tiles, --crop) changes a pixel. A region also samples the ring
// of pixels around it that its filter reaches, so that its border pixels get every sample they
// would have in the whole image.
// Corner samples lie on a lattice of spacing 2^-max_level pixel (1 for corners); a lattice
// point's value is a pure function of the point (its jitter too: a hash of the point and the
// seed, none on the image border), so sharing and the thread count cannot change an image.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "camera/film.h"
#include "camera/pixel_filter.h"
#include "camera/splat_film.h"
#include "math/vector.h"
#include "util/enum_names.h"

namespace candela {

enum class AntialiasingMode { none, uniform, jittered, corners, adaptive };

struct AntialiasingSettings {
  AntialiasingMode mode = AntialiasingMode::none;
  int n = 2;                         // uniform, jittered: n×n samples per pixel
  int max_level = 2;                 // adaptive: at most 2^max_level × 2^max_level leaf squares per pixel
  Color threshold{0.25, 0.20, 0.4};  // adaptive: contrast thresholds per channel
  bool jitter = false;               // corners, adaptive: jitter the interior lattice points
  std::string filter = "box";        // every mode: the reconstruction filter
  PixelFilterParameters filter_parameters;
};

inline constexpr auto kAntialiasingModeNames =
    enum_names<AntialiasingMode>({{AntialiasingMode::none, "none"},
                                  {AntialiasingMode::uniform, "uniform"},
                                  {AntialiasingMode::jittered, "jittered"},
                                  {AntialiasingMode::corners, "corners"},
                                  {AntialiasingMode::adaptive, "adaptive"}});

// Traces one primary ray through image point (x, y) — pixels, (0, 0) the top-left corner of the
// image — and returns its radiance. Called concurrently from several threads.
using RadianceFunction = std::function<Color(double x, double y)>;

struct SamplingResult {
  uint64_t traced = 0;  // radiance calls in total (the ring around a region included)
  // Region-sized, row by row. traced_per_pixel: the rays traced for each pixel; a shared
  // lattice sample counts for the pixel whose square holds it, the points on the right and
  // bottom edges of the image going to the last column / row, so that over the whole image the
  // counts sum to `traced` and do not depend on which thread asked first (samples of the ring
  // outside a region count for no pixel of it). samples_per_pixel: the distinct samples the
  // pixel's own square took (shared ones included; not those a wide filter brings in from the
  // neighbours).
  std::vector<uint32_t> traced_per_pixel;
  std::vector<uint32_t> samples_per_pixel;
};

struct SamplingRegion {
  int x0 = 0, y0 = 0;                     // the film's top-left pixel in the image
  int image_width = 0, image_height = 0;  // the whole image (its border gets no jitter)
};

// Fills film (the region's size) in parallel tiles of tile_size pixels; tile_done, when set, is
// called once per finished tile (sampling_tile_count of them). After Ctrl-C the pixels of the
// tiles not begun stay black. Throws std::invalid_argument for an unknown filter.
SamplingResult sample_image(const AntialiasingSettings& settings, uint64_t seed, const SamplingRegion& region,
                            int tile_size, const RadianceFunction& radiance, Film& film,
                            const std::function<void()>& tile_done = {});

// The hash of a lattice point's key (iy << 32 | ix) in the adaptive sampler's cache: every bit
// of the key reaches the low bits, where the hash table picks its bucket.
uint64_t lattice_key_hash(uint64_t key);

// The pixels whose samples sample_image takes for a width × height film at region: the region
// and the ring its filter reaches, within the image.
PixelBox sampled_pixels(const AntialiasingSettings& settings, const SamplingRegion& region, int width,
                        int height);

// Number of tiles sample_image uses for a width × height film at region.
int64_t sampling_tile_count(const AntialiasingSettings& settings, const SamplingRegion& region, int width,
                            int height, int tile_size);

// Number of tile_size tiles that cover a width × height rectangle.
int64_t tile_count(int width, int height, int tile_size);

}  // namespace candela
