// Anti-aliasing (SPEC §6; 000 §5.8; 001): how many primary rays each pixel takes, where, and how
// they combine into the pixel's value.
//   none      one ray through the pixel centre;
//   uniform   n×n sub-pixel centres;  jittered: one random point in each of the n×n sub-cells
//             (the pixel's own random stream); both weighted by the pixel filter, normalised over
//             the pixel's own samples;
//   corners   rays through the pixel corners, shared with the neighbours: (W+1)(H+1) rays;
//   adaptive  corner rays; a square splits into four while the contrast
//             C = (Imax − Imin) / (Imax + Imin) of any channel over its four corners exceeds that
//             channel's threshold and its level is below max_level; every sample is traced once
//             and reused within and across pixels; pixel = area-weighted mean of its leaf
//             squares, each leaf the mean of its four corners (001's worked example).
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
  std::string filter = "box";        // uniform, jittered
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
  uint64_t traced = 0;  // radiance calls in total
  // Region-sized, row by row. traced_per_pixel: the rays traced for each pixel; a shared
  // lattice sample counts for the pixel whose square holds it, the points on the right and
  // bottom edges of the region going to the last column / row, so the counts sum to `traced`
  // and do not depend on which thread asked first. samples_per_pixel: the distinct samples
  // each pixel's value used (shared ones included).
  std::vector<uint32_t> traced_per_pixel;
  std::vector<uint32_t> samples_per_pixel;
};

struct SamplingRegion {
  int x0 = 0, y0 = 0;                     // the film's top-left pixel in the image
  int image_width = 0, image_height = 0;  // the whole image (its border gets no jitter)
};

// Fills film (the region's size) in parallel tiles of tile_size pixels; tile_done, when set, is
// called once per finished tile.
SamplingResult sample_image(const AntialiasingSettings& settings, uint64_t seed, const SamplingRegion& region,
                            int tile_size, const RadianceFunction& radiance, Film& film,
                            const std::function<void()>& tile_done = {});

// The hash of a lattice point's key (iy << 32 | ix) in the adaptive sampler's cache: every bit
// of the key reaches the low bits, where the hash table picks its bucket.
uint64_t lattice_key_hash(uint64_t key);

// Number of tiles sample_image uses for a film of this size.
int64_t sampling_tile_count(int width, int height, int tile_size);

}  // namespace candela
