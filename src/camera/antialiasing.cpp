#include "camera/antialiasing.h"

#include <tbb/concurrent_hash_map.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <memory>

#include "math/pcg32.h"
#include "util/cancellation.h"

namespace candela {

namespace {

uint64_t mix64(uint64_t z) {  // splitmix64's finaliser
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

}  // namespace

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

double channel_contrast(double a, double b, double c, double d) {
  const double high = std::max({a, b, c, d});
  const double low = std::min({a, b, c, d});
  const double sum = high + low;
  return sum > 0 ? (high - low) / sum : 0.0;
}

bool exceeds(const Color& threshold, const Color& c00, const Color& c10, const Color& c01, const Color& c11) {
  for (int channel = 0; channel < 3; ++channel)
    if (channel_contrast(c00[channel], c10[channel], c01[channel], c11[channel]) > threshold[channel])
      return true;
  return false;
}

// Once cancel_requested() (Ctrl-C), tiles not yet begun are skipped: they keep the film's black and
// get no tile_done.
template <typename PixelFunction>
void for_each_tile(int width, int height, int tile, const std::function<void()>& tile_done,
                   const PixelFunction& pixel) {
  const int tiles_x = (width + tile - 1) / tile;
  const int64_t count = sampling_tile_count(width, height, tile);
  tbb::parallel_for(int64_t(0), count, [&](int64_t index) {
    if (cancel_requested()) return;  // Ctrl-C: the tiles not begun stay black
    const int x_begin = static_cast<int>(index % tiles_x) * tile;
    const int y_begin = static_cast<int>(index / tiles_x) * tile;
    const int x_end = std::min(x_begin + tile, width);
    const int y_end = std::min(y_begin + tile, height);
    for (int y = y_begin; y < y_end; ++y)
      for (int x = x_begin; x < x_end; ++x) pixel(x, y);
    if (tile_done) tile_done();
  });
}

// none, uniform, jittered: each pixel alone.
void sample_pixels(const AntialiasingSettings& settings, uint64_t seed, const SamplingRegion& region,
                   int tile, const RadianceFunction& radiance, Film& film, SamplingResult& result,
                   const std::function<void()>& tile_done) {
  const bool single = settings.mode == AntialiasingMode::none;
  const int n = single ? 1 : settings.n;
  const bool jittered = settings.mode == AntialiasingMode::jittered;
  const std::unique_ptr<PixelFilter> filter =
      single ? nullptr : create_pixel_filter(settings.filter, settings.filter_parameters);
  for_each_tile(film.width(), film.height(), tile, tile_done, [&](int px, int py) {
    const int x = region.x0 + px, y = region.y0 + py;
    const std::size_t index = std::size_t(py) * film.width() + px;
    result.traced_per_pixel[index] = result.samples_per_pixel[index] = static_cast<uint32_t>(n * n);
    if (single) {
      film.at(px, py) = radiance(x + 0.5, y + 0.5);
      return;
    }
    Pcg32 rng = pixel_rng(seed, static_cast<uint32_t>(x), static_cast<uint32_t>(y));
    Color weighted, plain;
    double weight_sum = 0;
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) {
        const double u = jittered ? rng.next_double() : 0.5;
        const double v = jittered ? rng.next_double() : 0.5;
        const double dx = (i + u) / n, dy = (j + v) / n;
        const Color value = radiance(x + dx, y + dy);
        const double weight = filter->evaluate(dx - 0.5, dy - 0.5);
        weighted += value * weight;
        weight_sum += weight;
        plain += value;
      }
    }
    // A filter that gives the pixel's own samples no net weight falls back to the plain mean.
    film.at(px, py) = weight_sum > 1e-12 ? weighted / weight_sum : plain / double(n * n);
  });
}

// corners: the (W+1)×(H+1) lattice of the region's pixel corners, traced once by rows.
void sample_corners(const AntialiasingSettings& settings, uint64_t seed, const SamplingRegion& region,
                    int tile, const RadianceFunction& radiance, Film& film, SamplingResult& result,
                    const std::function<void()>& tile_done) {
  const int width = film.width(), height = film.height();
  const Lattice lattice{1, settings.jitter, seed, region.image_width, region.image_height};
  std::vector<Color> corners(std::size_t(width + 1) * (height + 1));
  tbb::parallel_for(0, height + 1, [&](int j) {
    if (cancel_requested()) return;
    for (int i = 0; i <= width; ++i) {
      double x, y;
      lattice.position(region.x0 + i, region.y0 + j, x, y);
      corners[std::size_t(j) * (width + 1) + i] = radiance(x, y);
    }
  });
  for (int j = 0; j <= height; ++j)
    for (int i = 0; i <= width; ++i)
      ++result.traced_per_pixel[std::size_t(std::min(j, height - 1)) * width + std::min(i, width - 1)];
  for_each_tile(width, height, tile, tile_done, [&](int px, int py) {
    const auto corner = [&](int i, int j) { return corners[std::size_t(py + j) * (width + 1) + px + i]; };
    film.at(px, py) = (corner(0, 0) + corner(1, 0) + corner(0, 1) + corner(1, 1)) / 4.0;
    result.samples_per_pixel[std::size_t(py) * width + px] = 4;
  });
}

// adaptive: one cache of lattice values for the whole region.
class AdaptiveSampler {
 public:
  AdaptiveSampler(const AntialiasingSettings& settings, uint64_t seed, const SamplingRegion& region,
                  const RadianceFunction& radiance, const Film& film, SamplingResult& result)
      : settings_(settings),
        region_(region),
        radiance_(radiance),
        width_(film.width()),
        height_(film.height()),
        result_(result),
        traced_(std::size_t(film.width()) * film.height()) {
    const int64_t scale = int64_t(1) << settings.max_level;
    lattice_ = {scale, settings.jitter, seed, region.image_width * scale, region.image_height * scale};
    // Room for the corners and some subdivision from the start: growing the table while every
    // thread inserts costs more than the tracing near edges.
    cache_.rehash(std::size_t(film.width() + 1) * (film.height() + 1) * 2);
  }

  Color pixel(int px, int py) {
    const int64_t s = lattice_.scale;
    const int64_t ix = (region_.x0 + px) * s, iy = (region_.y0 + py) * s;
    std::vector<uint64_t> used;
    const Color value = square(ix, iy, s, 0, value_at(ix, iy, used), value_at(ix + s, iy, used),
                               value_at(ix, iy + s, used), value_at(ix + s, iy + s, used), used);
    std::sort(used.begin(), used.end());
    result_.samples_per_pixel[std::size_t(py) * width_ + px] =
        static_cast<uint32_t>(std::unique(used.begin(), used.end()) - used.begin());
    return value;
  }

  void finish() {
    for (std::size_t i = 0; i < traced_.size(); ++i) result_.traced_per_pixel[i] = traced_[i].load();
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

  Color square(int64_t ix, int64_t iy, int64_t size, int level, const Color& c00, const Color& c10,
               const Color& c01, const Color& c11, std::vector<uint64_t>& used) {
    if (level >= settings_.max_level || !exceeds(settings_.threshold, c00, c10, c01, c11))
      return (c00 + c10 + c01 + c11) / 4.0;
    const int64_t h = size / 2;
    const Color top = value_at(ix + h, iy, used), left = value_at(ix, iy + h, used);
    const Color centre = value_at(ix + h, iy + h, used);
    const Color right = value_at(ix + size, iy + h, used), bottom = value_at(ix + h, iy + size, used);
    // Four equal areas: the area-weighted mean is the plain mean of the quadrants.
    return (square(ix, iy, h, level + 1, c00, top, left, centre, used) +
            square(ix + h, iy, h, level + 1, top, c10, centre, right, used) +
            square(ix, iy + h, h, level + 1, left, centre, c01, bottom, used) +
            square(ix + h, iy + h, h, level + 1, centre, right, bottom, c11, used)) /
           4.0;
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
      const int64_t s = lattice_.scale;
      const int64_t px = std::min<int64_t>(ix / s - region_.x0, width_ - 1);
      const int64_t py = std::min<int64_t>(iy / s - region_.y0, height_ - 1);
      traced_[std::size_t(py) * width_ + px].fetch_add(1, std::memory_order_relaxed);
    }
    return writer->second;
  }

  const AntialiasingSettings& settings_;
  SamplingRegion region_;
  const RadianceFunction& radiance_;
  int width_, height_;
  SamplingResult& result_;
  Lattice lattice_;
  Cache cache_;
  std::vector<std::atomic<uint32_t>> traced_;
};

}  // namespace

int64_t sampling_tile_count(int width, int height, int tile_size) {
  return int64_t((width + tile_size - 1) / tile_size) * ((height + tile_size - 1) / tile_size);
}

SamplingResult sample_image(const AntialiasingSettings& settings, uint64_t seed, const SamplingRegion& region,
                            int tile_size, const RadianceFunction& radiance, Film& film,
                            const std::function<void()>& tile_done) {
  SamplingResult result;
  const std::size_t pixels = std::size_t(film.width()) * film.height();
  result.traced_per_pixel.assign(pixels, 0);
  result.samples_per_pixel.assign(pixels, 0);
  if (pixels == 0) return result;
  std::atomic<uint64_t> traced{0};
  const RadianceFunction counted = [&](double x, double y) {
    traced.fetch_add(1, std::memory_order_relaxed);
    return radiance(x, y);
  };
  switch (settings.mode) {
    case AntialiasingMode::none:
    case AntialiasingMode::uniform:
    case AntialiasingMode::jittered:
      sample_pixels(settings, seed, region, tile_size, counted, film, result, tile_done);
      break;
    case AntialiasingMode::corners:
      sample_corners(settings, seed, region, tile_size, counted, film, result, tile_done);
      break;
    case AntialiasingMode::adaptive: {
      AdaptiveSampler sampler(settings, seed, region, counted, film, result);
      for_each_tile(film.width(), film.height(), tile_size, tile_done,
                    [&](int px, int py) { film.at(px, py) = sampler.pixel(px, py); });
      sampler.finish();
      break;
    }
  }
  result.traced = traced.load();
  return result;
}

}  // namespace candela
