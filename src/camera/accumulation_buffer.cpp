#include "camera/accumulation_buffer.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <memory>

#include "camera/contrast.h"
#include "math/pcg32.h"
#include "util/cancellation.h"
#include "util/hash.h"

namespace candela {

bool drawn_in_passes(const AntialiasingSettings& settings) {
  switch (settings.mode) {
    case AntialiasingMode::jittered:
      return true;
    case AntialiasingMode::corners:
    case AntialiasingMode::adaptive:
      return settings.jitter;
    case AntialiasingMode::none:
    case AntialiasingMode::uniform:
      return false;
  }
  return false;
}

PassSchedule::PassSchedule(const AntialiasingSettings& settings, uint64_t seed)
    : stream_(mix64(seed ^ 0x6a09e667f3bcc909ULL)) {
  if (settings.mode == AntialiasingMode::jittered) {
    side_ = settings.n;
    first_ = most_ = settings.n * settings.n;
    return;
  }
  levels_ = settings.mode == AntialiasingMode::corners ? 1 : std::max(settings.max_level, 1);
  side_ = 1 << levels_;
  first_ = 4;
  most_ = side_ * side_;
}

PassOffset PassSchedule::offset(int pass) const {
  int cell_x = pass % side_, cell_y = pass / side_;
  if (levels_ > 0) {
    // The nested order: digit l of the pass in base 4 picks the quadrant at level l + 1, XORed
    // with two bits hashed from the digits before it (a bijection for each prefix, so every
    // 4^l first passes still fill every cell of level l, and the quadrant of a finer level is
    // uniformly random: a pixel stopped at level l has each sample uniform in its cell).
    cell_x = cell_y = 0;
    uint64_t prefix = 1;  // the digits so far behind a leading 1, so that levels differ
    for (int level = 0; level < levels_; ++level) {
      const int digit = (pass >> (2 * level)) & 3;
      const int quadrant = digit ^ static_cast<int>(mix64(stream_ ^ mix64(prefix)) & 3);
      cell_x = 2 * cell_x + (quadrant & 1);
      cell_y = 2 * cell_y + (quadrant >> 1);
      prefix = prefix << 2 | static_cast<uint64_t>(digit);
    }
  }
  Pcg32 jitter(stream_, static_cast<uint64_t>(pass));
  const double u = jitter.next_double(), v = jitter.next_double();
  return {(cell_x + u) / side_, (cell_y + v) / side_};
}

namespace {

// The first four passes' samples over the image: one lattice of spacing about ½ — a pixel's
// sample in quadrant (i, j) is its point (2x + i, 2y + j), every pixel's at the same place within
// it (one offset a pass) — whose squares of four neighbouring points the contrast test reads.
class FirstPassLattice {
 public:
  FirstPassLattice(const PassSchedule& schedule, const std::vector<std::vector<Color>>& values,
                   const PixelBox& box)
      : values_(values), box_(box) {
    for (int pass = 0; pass < 4; ++pass) {  // each quadrant once (the nested order)
      const PassOffset offset = schedule.offset(pass);
      pass_of_[offset.dy >= 0.5 ? 1 : 0][offset.dx >= 0.5 ? 1 : 0] = pass;
    }
  }

  // Whether pixel (x, y) takes every pass: the contrast of a square reaching into it — its own
  // four samples, or its nearest ones with its neighbours', so that an edge passing between two
  // pixels' samples refines both — exceeds the threshold. Points outside the box are outside the
  // image (the box holds the ring around every pixel tested).
  bool refines(const Color& threshold, int x, int y) const {
    const int64_t low_x = 2 * int64_t(box_.x0), high_x = 2 * int64_t(box_.x1) - 1;
    const int64_t low_y = 2 * int64_t(box_.y0), high_y = 2 * int64_t(box_.y1) - 1;
    for (int64_t square_y = 2 * int64_t(y) - 1; square_y <= 2 * int64_t(y) + 1; ++square_y)
      for (int64_t square_x = 2 * int64_t(x) - 1; square_x <= 2 * int64_t(x) + 1; ++square_x) {
        if (square_x < low_x || square_x + 1 > high_x || square_y < low_y || square_y + 1 > high_y) continue;
        if (contrast_exceeds(threshold, point(square_x, square_y), point(square_x + 1, square_y),
                             point(square_x, square_y + 1), point(square_x + 1, square_y + 1)))
          return true;
      }
    return false;
  }

 private:
  const Color& point(int64_t lattice_x, int64_t lattice_y) const {
    const auto x = static_cast<int>(lattice_x >> 1), y = static_cast<int>(lattice_y >> 1);
    return values_[std::size_t(pass_of_[lattice_y & 1][lattice_x & 1])]
                  [std::size_t(y - box_.y0) * box_.width() + (x - box_.x0)];
  }

  const std::vector<std::vector<Color>>& values_;
  PixelBox box_;
  int pass_of_[2][2] = {};
};

}  // namespace

PixelBox pixels_drawn_in_passes(const AntialiasingSettings& settings, const SamplingRegion& region, int width,
                                int height) {
  const PassSchedule schedule(settings, 0);
  const PixelBox sampled = sampled_pixels(settings, region, width, height);
  if (schedule.passes() == schedule.first_passes() || sampled.empty()) return sampled;
  return sampled.grown(1).clipped({0, 0, region.image_width, region.image_height});
}

uint64_t accumulation_bytes(const AntialiasingSettings& settings, const PixelBox& box) {
  const PassSchedule schedule(settings, 0);
  const bool refines = schedule.passes() > schedule.first_passes();
  // SplatFilm's sums: Σ w·L, Σ w, the own samples' Σ a·L and Σ a.
  constexpr uint64_t kSums = 2 * sizeof(Color) + 2 * sizeof(double);
  const uint64_t per_pixel =
      sizeof(Color) + sizeof(uint8_t) + sizeof(double) + kSums +
      (refines ? static_cast<uint64_t>(schedule.first_passes()) * sizeof(Color) + sizeof(uint8_t) : 0);
  return static_cast<uint64_t>(std::max(box.width(), 0)) * static_cast<uint64_t>(std::max(box.height(), 0)) *
         per_pixel;
}

PassesResult accumulate_passes(const AntialiasingSettings& settings, uint64_t seed,
                               const SamplingRegion& region, const PassDrawing& draw, Film& film) {
  PassesResult result;
  const PassSchedule schedule(settings, seed);
  result.most_passes = schedule.passes();
  if (film.width() <= 0 || film.height() <= 0) return result;
  const std::unique_ptr<PixelFilter> filter =
      create_pixel_filter(settings.filter, settings.filter_parameters);
  const PixelBox target{region.x0, region.y0, region.x0 + film.width(), region.y0 + film.height()};
  const PixelBox sampled = sampled_pixels(settings, region, film.width(), film.height());
  const PixelBox box = pixels_drawn_in_passes(settings, region, film.width(), film.height());
  const std::size_t count = std::size_t(box.width()) * box.height();
  const auto index = [&](int x, int y) { return std::size_t(y - box.y0) * box.width() + (x - box.x0); };
  SplatFilm whole(target);
  // Rows of the image one class mod 2·reach + 1 apart reach no common pixel: their samples are
  // splatted in parallel, the classes one after the other, so a pixel's sums are added in the
  // same order whatever the threads and the region.
  const int classes = 2 * filter_reach(*filter) + 1;
  const auto splat = [&](const PassOffset& offset, const std::vector<Color>& values,
                         const std::vector<double>& weights) {
    for (int c = 0; c < classes; ++c) {
      const int first_row = box.y0 + ((c - box.y0) % classes + classes) % classes;
      if (first_row >= box.y1) continue;
      tbb::parallel_for(0, (box.y1 - 1 - first_row) / classes + 1, [&](int r) {
        const int y = first_row + r * classes;
        for (int x = box.x0; x < box.x1; ++x) {
          const std::size_t i = index(x, y);
          if (weights[i] > 0) whole.splat(*filter, x, y, offset.dx, offset.dy, weights[i], values[i]);
        }
      });
    }
  };
  const auto drawn = [&](int pass, const std::vector<uint8_t>& wanted, std::vector<Color>& values) {
    if (cancel_requested()) return false;  // Ctrl-C: no pass begun after it
    draw(pass, schedule.offset(pass), box, wanted, values);
    if (cancel_requested()) return false;  // and the pass it cut short (tiles missing) not splatted
    result.samples += static_cast<uint64_t>(std::count(wanted.begin(), wanted.end(), uint8_t(1)));
    ++result.passes;
    return true;
  };

  std::vector<uint8_t> wanted(count, 1);
  std::vector<Color> values(count);
  const bool refines = schedule.passes() > schedule.first_passes();
  if (!refines) {
    // Every pass for every pixel, each sample of weight 1 (jittered; corners; adaptive, L ≤ 1).
    const std::vector<double> weights(count, 1.0);
    for (int pass = 0; pass < schedule.passes() && drawn(pass, wanted, values); ++pass)
      splat(schedule.offset(pass), values, weights);
  } else {
    // The first four passes for every pixel, kept until the contrast test has chosen their weight.
    const int first = schedule.first_passes();
    std::vector<std::vector<Color>> first_values(static_cast<std::size_t>(first), std::vector<Color>(count));
    int first_drawn = 0;
    while (first_drawn < first && drawn(first_drawn, wanted, first_values[std::size_t(first_drawn)]))
      ++first_drawn;
    // Only the pixels within the filter's reach of the region are splatted; the ring beyond them
    // is drawn for the contrast test of their neighbours.
    std::vector<double> weights(count, 0.0);
    std::vector<uint8_t> refined(count, 0);
    const FirstPassLattice lattice(schedule, first_values, box);
    tbb::parallel_for(sampled.y0, sampled.y1, [&](int y) {
      for (int x = sampled.x0; x < sampled.x1; ++x) {
        const std::size_t i = index(x, y);
        refined[i] = first_drawn == first && lattice.refines(settings.threshold, x, y);
        weights[i] = refined[i] ? 1.0 / schedule.passes() : 1.0 / first;
      }
    });
    for (int pass = 0; pass < first_drawn; ++pass)
      splat(schedule.offset(pass), first_values[std::size_t(pass)], weights);
    for (int y = target.y0; y < target.y1; ++y)
      for (int x = target.x0; x < target.x1; ++x) result.refined_pixels += refined[index(x, y)];
    if (std::find(refined.begin(), refined.end(), uint8_t(1)) != refined.end()) {
      for (std::size_t i = 0; i < count; ++i)
        if (!refined[i]) weights[i] = 0;
      for (int pass = first; pass < schedule.passes() && drawn(pass, refined, values); ++pass)
        splat(schedule.offset(pass), values, weights);
    }
  }
  tbb::parallel_for(target.y0, target.y1, [&](int y) {
    for (int x = target.x0; x < target.x1; ++x) film.at(x - target.x0, y - target.y0) = whole.resolve(x, y);
  });
  return result;
}

}  // namespace candela
