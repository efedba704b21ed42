#include "camera/antialiasing.h"

#include <tbb/concurrent_hash_map.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <memory>

#include "camera/contrast.h"
#include "math/pcg32.h"
#include "util/cancellation.h"
#include "util/hash.h"

namespace candela {

uint64_t lattice_key_hash(uint64_t key) {
  return mix64(key);
}

namespace {

// Image coordinates of lattice point (ix, iy) of spacing 1/scale: a pure function of the point,
// the seed and the settings. Jitter moves interior points by up to half a lattice spacing.
struct Lattice {
  int64_t scale = 1;  // lattice points per pixel side
  bool jitter = false;
  uint64_t seed = 0;
  int64_t last_x = 0, last_y = 0;  // image border: ix in {0, last_x}, iy in {0, last_y}

  void position(int64_t ix, int64_t iy, double& x, double& y) const {
    x = double(ix) / double(scale);
    y = double(iy) / double(scale);
    if (!jitter || ix == 0 || iy == 0 || ix == last_x || iy == last_y) return;
    const uint64_t h =
        mix64(mix64(seed ^ 0x9e3779b97f4a7c15ULL) ^ (uint64_t(iy) << 32 | uint64_t(uint32_t(ix))));
    const double u = double(h >> 40) * 0x1p-24 - 0.5;
    const double v = double((h >> 16) & 0xffffff) * 0x1p-24 - 0.5;
    x += u / double(scale);
    y += v / double(scale);
  }
};

// A pixel's samples, handed to emit(dx, dy, a, value): offset (dx, dy) in [0, 1)² within the
// pixel, own weight a (1 for a point sample, the area for a leaf square).
using SampleSink = std::function<void(double dx, double dy, double a, const Color& value)>;

// Where a pixel's samples go: the film, the filter and the pixel.
struct PixelSplat {
  SplatFilm& film;
  const PixelFilter& filter;
  int x, y;
};

// none, uniform, jittered: each pixel alone, from its own random stream.
class PointSampler {
 public:
  PointSampler(const AntialiasingSettings& settings, uint64_t seed, const RadianceFunction& radiance)
      : single_(settings.mode == AntialiasingMode::none),
        n_(single_ ? 1 : settings.n),
        jittered_(settings.mode == AntialiasingMode::jittered),
        seed_(seed),
        radiance_(radiance) {}

  uint32_t samples_per_pixel() const { return static_cast<uint32_t>(n_ * n_); }

  void pixel(int x, int y, const SampleSink& emit) const {
    if (single_) return emit(0.5, 0.5, 1.0, radiance_(x + 0.5, y + 0.5));
    Pcg32 rng = pixel_rng(seed_, static_cast<uint32_t>(x), static_cast<uint32_t>(y));
    for (int j = 0; j < n_; ++j) {
      for (int i = 0; i < n_; ++i) {
        const double u = jittered_ ? rng.next_double() : 0.5;
        const double v = jittered_ ? rng.next_double() : 0.5;
        const double dx = (i + u) / n_, dy = (j + v) / n_;
        emit(dx, dy, 1.0, radiance_(x + dx, y + dy));
      }
    }
  }

 private:
  bool single_;
  int n_;
  bool jittered_;
  uint64_t seed_;
  const RadianceFunction& radiance_;
};

// corners (max_level 0) and adaptive: one cache of lattice values for the sampled pixels.
class LatticeSampler {
 public:
  LatticeSampler(const AntialiasingSettings& settings, uint64_t seed, const SamplingRegion& region,
                 const PixelBox& target, const PixelBox& sampled, const RadianceFunction& radiance)
      : max_level_(settings.mode == AntialiasingMode::corners ? 0 : settings.max_level),
        threshold_(settings.threshold),
        image_width_(region.image_width),
        image_height_(region.image_height),
        target_(target),
        radiance_(radiance),
        traced_(std::size_t(target.width()) * target.height()) {
    const int64_t scale = int64_t(1) << max_level_;
    lattice_ = {scale, settings.jitter, seed, region.image_width * scale, region.image_height * scale};
    // Room for the corners and some subdivision from the start: growing the table while every
    // thread inserts costs more than the tracing near edges.
    cache_.rehash(std::size_t(sampled.width() + 1) * (sampled.height() + 1) * 2);
  }

  // Emits the pixel's leaf squares, each at its centre with its area; returns how many distinct
  // lattice points its squares used.
  uint32_t pixel(int x, int y, const SampleSink& emit) {
    const int64_t s = lattice_.scale;
    const int64_t ix = x * s, iy = y * s;
    std::vector<uint64_t> used;
    const Leaf leaf{ix, iy, emit};
    square(leaf, ix, iy, s, 0, value_at(ix, iy, used), value_at(ix + s, iy, used), value_at(ix, iy + s, used),
           value_at(ix + s, iy + s, used), used);
    std::sort(used.begin(), used.end());
    return static_cast<uint32_t>(std::unique(used.begin(), used.end()) - used.begin());
  }

  uint32_t traced(int x, int y) const {
    return traced_[std::size_t(y - target_.y0) * target_.width() + (x - target_.x0)].load();
  }

 private:
  // TBB hashes an integer key to itself and picks buckets by its low bits: with the key (iy, ix)
  // every lattice column fell into one bucket chain, and a 1024² adaptive image took 20 times as
  // long in one region as in 64-pixel tiles (found measuring docs/distributed.md).
  struct KeyHash {
    static std::size_t hash(uint64_t key) { return static_cast<std::size_t>(lattice_key_hash(key)); }
    static bool equal(uint64_t a, uint64_t b) { return a == b; }
  };
  using Cache = tbb::concurrent_hash_map<uint64_t, Color, KeyHash>;

  struct Leaf {
    int64_t pixel_x, pixel_y;  // the pixel's corner on the lattice
    const SampleSink& emit;
  };

  void square(const Leaf& leaf, int64_t ix, int64_t iy, int64_t size, int level, const Color& c00,
              const Color& c10, const Color& c01, const Color& c11, std::vector<uint64_t>& used) {
    if (level >= max_level_ || !contrast_exceeds(threshold_, c00, c10, c01, c11)) {
      // The leaf at its (unjittered) centre, weighted by its area: exact binary fractions.
      const double s = double(lattice_.scale);
      const double dx = (double(ix - leaf.pixel_x) + double(size) / 2) / s;
      const double dy = (double(iy - leaf.pixel_y) + double(size) / 2) / s;
      const double side = double(size) / s;
      leaf.emit(dx, dy, side * side, (c00 + c10 + c01 + c11) / 4.0);
      return;
    }
    const int64_t h = size / 2;
    const Color top = value_at(ix + h, iy, used), left = value_at(ix, iy + h, used);
    const Color centre = value_at(ix + h, iy + h, used);
    const Color right = value_at(ix + size, iy + h, used), bottom = value_at(ix + h, iy + size, used);
    square(leaf, ix, iy, h, level + 1, c00, top, left, centre, used);
    square(leaf, ix + h, iy, h, level + 1, top, c10, centre, right, used);
    square(leaf, ix, iy + h, h, level + 1, left, centre, c01, bottom, used);
    square(leaf, ix + h, iy + h, h, level + 1, centre, right, bottom, c11, used);
  }

  Color value_at(int64_t ix, int64_t iy, std::vector<uint64_t>& used) {
    const uint64_t key = uint64_t(iy) << 32 | uint64_t(uint32_t(ix));
    used.push_back(key);
    {
      Cache::const_accessor reader;
      if (cache_.find(reader, key)) return reader->second;
    }
    Cache::accessor writer;  // held while tracing: a second asker waits, so each point is traced once
    if (cache_.insert(writer, key)) {
      double x, y;
      lattice_.position(ix, iy, x, y);
      writer->second = radiance_(x, y);
      // Counted for the image pixel whose square holds the point (the right and bottom image
      // edges for the last column and row), when that pixel is the region's.
      const int64_t s = lattice_.scale;
      const int px = static_cast<int>(std::min<int64_t>(ix / s, image_width_ - 1));
      const int py = static_cast<int>(std::min<int64_t>(iy / s, image_height_ - 1));
      if (target_.contains(px, py))
        traced_[std::size_t(py - target_.y0) * target_.width() + (px - target_.x0)].fetch_add(
            1, std::memory_order_relaxed);
    }
    return writer->second;
  }

  int max_level_;
  Color threshold_;
  int image_width_, image_height_;
  PixelBox target_;
  const RadianceFunction& radiance_;
  Lattice lattice_;
  Cache cache_;
  std::vector<std::atomic<uint32_t>> traced_;
};

// The image-aligned tiles of tile_size that cover `sampled`, row by row.
struct TileGrid {
  int tile = 1;
  int tx0 = 0, ty0 = 0, columns = 0, rows = 0;
  TileGrid(const PixelBox& sampled, int tile_size) : tile(tile_size) {
    if (sampled.empty()) return;
    tx0 = sampled.x0 / tile, ty0 = sampled.y0 / tile;
    columns = (sampled.x1 - 1) / tile - tx0 + 1;
    rows = (sampled.y1 - 1) / tile - ty0 + 1;
  }
  int64_t count() const { return int64_t(columns) * rows; }
  PixelBox at(int64_t index, const PixelBox& sampled) const {
    const int x0 = (tx0 + static_cast<int>(index % columns)) * tile;
    const int y0 = (ty0 + static_cast<int>(index / columns)) * tile;
    return PixelBox{x0, y0, x0 + tile, y0 + tile}.clipped(sampled);
  }
  int64_t index_of(int x, int y) const { return int64_t(y / tile - ty0) * columns + (x / tile - tx0); }
};

PixelBox image_box(const SamplingRegion& region) {
  return {0, 0, region.image_width, region.image_height};
}

PixelBox target_box(const SamplingRegion& region, int width, int height) {
  return {region.x0, region.y0, region.x0 + width, region.y0 + height};
}

}  // namespace

int64_t tile_count(int width, int height, int tile_size) {
  return int64_t((width + tile_size - 1) / tile_size) * ((height + tile_size - 1) / tile_size);
}

PixelBox sampled_pixels(const AntialiasingSettings& settings, const SamplingRegion& region, int width,
                        int height) {
  const auto filter = create_pixel_filter(settings.filter, settings.filter_parameters);
  return target_box(region, width, height).grown(filter_reach(*filter)).clipped(image_box(region));
}

int64_t sampling_tile_count(const AntialiasingSettings& settings, const SamplingRegion& region, int width,
                            int height, int tile_size) {
  return TileGrid(sampled_pixels(settings, region, width, height), tile_size).count();
}

SamplingResult sample_image(const AntialiasingSettings& settings, uint64_t seed, const SamplingRegion& region,
                            int tile_size, const RadianceFunction& radiance, Film& film,
                            const std::function<void()>& tile_done) {
  SamplingResult result;
  const std::size_t pixels = std::size_t(film.width()) * film.height();
  result.traced_per_pixel.assign(pixels, 0);
  result.samples_per_pixel.assign(pixels, 0);
  if (pixels == 0) return result;
  const std::unique_ptr<PixelFilter> filter =
      create_pixel_filter(settings.filter, settings.filter_parameters);
  const PixelBox target = target_box(region, film.width(), film.height());
  const PixelBox sampled = target.grown(filter_reach(*filter)).clipped(image_box(region));
  const int reach = filter_reach(*filter);
  std::atomic<uint64_t> traced{0};
  const RadianceFunction counted = [&](double x, double y) {
    traced.fetch_add(1, std::memory_order_relaxed);
    return radiance(x, y);
  };
  const bool lattice_mode =
      settings.mode == AntialiasingMode::corners || settings.mode == AntialiasingMode::adaptive;
  // The point sampler traces samples_per_pixel() rays a pixel, counted per tile below; the
  // lattice's samples, shared between pixels, are counted as they are traced.
  const PointSampler points(settings, seed, radiance);
  std::unique_ptr<LatticeSampler> lattice;
  if (lattice_mode)
    lattice = std::make_unique<LatticeSampler>(settings, seed, region, target, sampled, counted);

  const TileGrid tiles(sampled, std::max(tile_size, 1));
  std::vector<uint8_t> tile_finished(static_cast<std::size_t>(tiles.count()), 0);
  SplatFilm whole(target);
  // A tile splats into the pixels within `reach` of its own. Tiles k apart (k − 1 tiles between
  // them) reach no common pixel when (k − 1)·tile ≥ 2·reach: the tiles of one class
  // (tx mod k, ty mod k) splat into the film in parallel without sharing a pixel, and the classes
  // go one after the other in a fixed order, so every pixel gets its sums in the same order
  // whatever the thread count — and whatever region is asked for, the tiles being aligned on the
  // image's own grid.
  const int k = 1 + (2 * reach + tiles.tile - 1) / tiles.tile;
  std::vector<std::vector<int64_t>> classes(std::size_t(k) * k);
  for (int64_t index = 0; index < tiles.count(); ++index) {
    const int tx = tiles.tx0 + static_cast<int>(index % tiles.columns);
    const int ty = tiles.ty0 + static_cast<int>(index / tiles.columns);
    classes[std::size_t(ty % k) * k + std::size_t(tx % k)].push_back(index);
  }
  for (const std::vector<int64_t>& members : classes) {
    tbb::parallel_for(std::size_t(0), members.size(), [&](std::size_t member) {
      if (cancel_requested()) return;  // Ctrl-C: the tiles not begun stay black
      const int64_t index = members[member];
      const PixelBox tile = tiles.at(index, sampled);
      uint64_t tile_traced = 0;
      for (int y = tile.y0; y < tile.y1; ++y)
        for (int x = tile.x0; x < tile.x1; ++x) {
          // One pointer captured, which std::function keeps inline: capturing the four by reference
          // made it allocate once a pixel.
          const PixelSplat here{whole, *filter, x, y};
          const SampleSink emit = [&here](double dx, double dy, double a, const Color& value) {
            here.film.splat(here.filter, here.x, here.y, dx, dy, a, value);
          };
          const bool counted_here = target.contains(x, y);
          const std::size_t pixel =
              counted_here ? std::size_t(y - target.y0) * target.width() + (x - target.x0) : 0;
          if (lattice) {
            const uint32_t used = lattice->pixel(x, y, emit);
            if (counted_here) result.samples_per_pixel[pixel] = used;
          } else {
            points.pixel(x, y, emit);
            tile_traced += points.samples_per_pixel();
            if (counted_here)
              result.samples_per_pixel[pixel] = result.traced_per_pixel[pixel] = points.samples_per_pixel();
          }
        }
      traced.fetch_add(tile_traced, std::memory_order_relaxed);
      tile_finished[static_cast<std::size_t>(index)] = 1;
      if (tile_done) tile_done();
    });
  }
  tbb::parallel_for(target.y0, target.y1, [&](int y) {
    for (int x = target.x0; x < target.x1; ++x) {
      const bool finished = tile_finished[static_cast<std::size_t>(tiles.index_of(x, y))] != 0;
      film.at(x - target.x0, y - target.y0) = finished ? whole.resolve(x, y) : Color();
      if (lattice) {
        const std::size_t pixel = std::size_t(y - target.y0) * target.width() + (x - target.x0);
        result.traced_per_pixel[pixel] = lattice->traced(x, y);
      }
    }
  });
  result.traced = traced.load();
  return result;
}

}  // namespace candela
