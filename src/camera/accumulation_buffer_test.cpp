#include "camera/accumulation_buffer.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <mutex>
#include <set>
#include <utility>
#include <vector>

#include "half_plane.h"

// Its own namespace: the unity build compiles it with camera/antialiasing_test.cpp (the same names).
namespace candela::accumulation_buffer_test {
namespace {

using testing::HalfPlane;

constexpr int kWidth = 16, kHeight = 12;

AntialiasingSettings jittered(int n) {
  AntialiasingSettings settings;
  settings.mode = AntialiasingMode::jittered;
  settings.n = n;
  return settings;
}

AntialiasingSettings jittered_lattice(AntialiasingMode mode, int max_level) {
  AntialiasingSettings settings;
  settings.mode = mode;
  settings.max_level = max_level;
  settings.jitter = true;
  return settings;
}

// The cell of a side × side grid that an offset lies in.
std::pair<int, int> cell_of(const PassOffset& offset, int side) {
  return {static_cast<int>(std::floor(offset.dx * side)), static_cast<int>(std::floor(offset.dy * side))};
}

TEST(AccumulationBuffer, OnlyJitteredSamplesAreDrawnInPasses) {
  AntialiasingSettings settings;
  for (const AntialiasingMode mode : {AntialiasingMode::none, AntialiasingMode::uniform}) {
    settings.mode = mode;
    EXPECT_FALSE(drawn_in_passes(settings));
  }
  EXPECT_TRUE(drawn_in_passes(jittered(2)));
  for (const AntialiasingMode mode : {AntialiasingMode::corners, AntialiasingMode::adaptive}) {
    settings = jittered_lattice(mode, 2);
    EXPECT_TRUE(drawn_in_passes(settings));
    settings.jitter = false;
    EXPECT_FALSE(drawn_in_passes(settings));
  }
}

// Jittered n: pass k in cell (k mod n, k div n), at a point that depends on the seed alone.
TEST(AccumulationBuffer, JitteredPassesTakeEachCellOnceAtAPointOfTheSeed) {
  for (const int n : {1, 3, 4}) {
    const PassSchedule schedule(jittered(n), 11), same(jittered(n), 11), other(jittered(n), 12);
    ASSERT_EQ(schedule.passes(), n * n);
    ASSERT_EQ(schedule.first_passes(), n * n);
    int differs = 0;
    for (int pass = 0; pass < n * n; ++pass) {
      const PassOffset offset = schedule.offset(pass);
      EXPECT_GE(offset.dx, 0.0);
      EXPECT_LT(offset.dx, 1.0);
      EXPECT_GE(offset.dy, 0.0);
      EXPECT_LT(offset.dy, 1.0);
      EXPECT_EQ(cell_of(offset, n), std::make_pair(pass % n, pass / n)) << "n=" << n << " pass " << pass;
      EXPECT_EQ(offset.dx, same.offset(pass).dx);
      EXPECT_EQ(offset.dy, same.offset(pass).dy);
      differs += offset.dx != other.offset(pass).dx || offset.dy != other.offset(pass).dy;
    }
    EXPECT_EQ(differs, n * n);
  }
}

// The lattice modes' nested order: the first 4^l passes hold one point in each cell of the
// 2^l × 2^l grid for every level l, and the first pass's point is spread over the finest cells
// from seed to seed (the quadrants of the finer levels are scrambled, not always the first).
TEST(AccumulationBuffer, NestedPassesFillEveryCellOfEveryLevel) {
  for (const uint64_t seed : {0u, 5u, 99u}) {
    const PassSchedule schedule(jittered_lattice(AntialiasingMode::adaptive, 3), seed);
    ASSERT_EQ(schedule.first_passes(), 4);
    ASSERT_EQ(schedule.passes(), 64);
    for (int level = 1; level <= 3; ++level) {
      const int side = 1 << level;
      std::set<std::pair<int, int>> cells;
      for (int pass = 0; pass < side * side; ++pass) cells.insert(cell_of(schedule.offset(pass), side));
      EXPECT_EQ(cells.size(), std::size_t(side * side)) << "level " << level << ", seed " << seed;
    }
  }
  const PassSchedule corners(jittered_lattice(AntialiasingMode::corners, 3), 1);
  EXPECT_EQ(corners.passes(), 4);
  std::set<std::pair<int, int>> quadrants;
  for (int pass = 0; pass < 4; ++pass) quadrants.insert(cell_of(corners.offset(pass), 2));
  EXPECT_EQ(quadrants.size(), 4u);
  EXPECT_EQ(PassSchedule(jittered_lattice(AntialiasingMode::adaptive, 1), 1).passes(), 4);
  std::set<std::pair<int, int>> first_cells;
  for (uint64_t seed = 0; seed < 64; ++seed)
    first_cells.insert(
        cell_of(PassSchedule(jittered_lattice(AntialiasingMode::adaptive, 3), seed).offset(0), 8));
  EXPECT_GT(first_cells.size(), 30u);  // uniform over 64 cells: about 41 distinct
}

struct Accumulated {
  Film film{kWidth, kHeight};
  PassesResult result;
  std::vector<uint64_t> wanted_per_pass;  // how many samples each pass was asked for
};

// The passes of a scene given as a function of the image point.
template <typename Scene>
Accumulated accumulate(const AntialiasingSettings& settings, const Scene& scene, const SamplingRegion& region,
                       int width = kWidth, int height = kHeight) {
  Accumulated out;
  out.film = Film(width, height);
  const PassDrawing draw = [&](int pass, const PassOffset& offset, const PixelBox& box,
                               const std::vector<uint8_t>& wanted, std::vector<Color>& values) {
    EXPECT_EQ(static_cast<std::size_t>(pass), out.wanted_per_pass.size());
    out.wanted_per_pass.push_back(
        static_cast<uint64_t>(std::count(wanted.begin(), wanted.end(), uint8_t(1))));
    for (int y = box.y0; y < box.y1; ++y)
      for (int x = box.x0; x < box.x1; ++x) {
        const std::size_t i = std::size_t(y - box.y0) * box.width() + (x - box.x0);
        if (wanted[i]) values[i] = scene(x + offset.dx, y + offset.dy);
      }
  };
  out.result = accumulate_passes(settings, 7, region, draw, out.film);
  return out;
}

template <typename Scene>
Accumulated accumulate(const AntialiasingSettings& settings, const Scene& scene) {
  return accumulate(settings, scene, SamplingRegion{0, 0, kWidth, kHeight});
}

// As the ray tracers' jittered samples (camera/antialiasing_test.cpp): at most the 2n − 1
// sub-cells an edge crosses are wrong, each by 1/n² — whatever point the pass drew in them.
TEST(AccumulationBuffer, JitteredPassesEstimateEachPixelsCoverage) {
  for (const double degrees : {10.0, 30.0, 45.0, 80.0}) {
    const HalfPlane edge(degrees, kWidth, kHeight);
    for (const int n : {1, 2, 4, 8}) {
      const Accumulated a = accumulate(jittered(n), edge);
      EXPECT_EQ(a.result.passes, n * n);
      EXPECT_EQ(a.result.samples, uint64_t(kWidth * kHeight * n * n));  // the box reaches no ring
      double worst = 0;
      for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x)
          worst = std::max(worst, std::fabs(a.film.at(x, y).r - edge.covered(x, y)));
      EXPECT_LE(worst, (2.0 * n - 1) / (n * n) + 1e-9) << "n=" << n << " at " << degrees << "°";
    }
  }
}

// Adaptive with jitter: four passes everywhere, the 4^L passes only in the pixels where the
// contrast of the four passes' samples, theirs and their neighbours' nearest, exceeds the
// threshold — every pixel the edge crosses (it separates two neighbouring samples there), each
// then within (2·2^L − 1)/4^L of its coverage, and some of their neighbours; elsewhere the
// samples agree and the pixel is exact.
TEST(AccumulationBuffer, AdaptivePassesRefineOnlyThePixelsTheContrastTestPicks) {
  constexpr int kLevel = 3, kSide = 1 << kLevel;
  for (const double degrees : {10.0, 30.0, 45.0, 80.0}) {
    const HalfPlane edge(degrees, kWidth, kHeight);
    const Accumulated a = accumulate(jittered_lattice(AntialiasingMode::adaptive, kLevel), edge);
    ASSERT_EQ(a.result.passes, kSide * kSide);
    for (int pass = 0; pass < 4; ++pass)
      EXPECT_EQ(a.wanted_per_pass[std::size_t(pass)], uint64_t(kWidth * kHeight));
    for (int pass = 4; pass < kSide * kSide; ++pass)
      EXPECT_EQ(a.wanted_per_pass[std::size_t(pass)], a.result.refined_pixels);
    EXPECT_EQ(a.result.samples,
              uint64_t(4 * kWidth * kHeight) + (kSide * kSide - 4) * a.result.refined_pixels);
    uint64_t edge_pixels = 0;
    for (int y = 0; y < kHeight; ++y)
      for (int x = 0; x < kWidth; ++x) {
        const double covered = edge.covered(x, y), value = a.film.at(x, y).r;
        if (covered == 0 || covered == 1) {
          EXPECT_EQ(value, covered) << x << "," << y;
          continue;
        }
        ++edge_pixels;
        EXPECT_LE(std::fabs(value - covered), (2.0 * kSide - 1) / (kSide * kSide) + 1e-9)
            << x << "," << y << " at " << degrees << "°";
      }
    EXPECT_GE(a.result.refined_pixels, edge_pixels);
    EXPECT_LE(a.result.refined_pixels, 3 * edge_pixels);
    std::printf("  adaptive L=3 at %4.0f°: %llu of %d pixels refined, %llu on the edge\n", degrees,
                static_cast<unsigned long long>(a.result.refined_pixels), kWidth * kHeight,
                static_cast<unsigned long long>(edge_pixels));
  }
  // A flat image: four passes and no more.
  const Accumulated flat = accumulate(jittered_lattice(AntialiasingMode::adaptive, kLevel),
                                      [](double, double) { return Color(0.3); });
  EXPECT_EQ(flat.result.passes, 4);
  EXPECT_EQ(flat.result.refined_pixels, 0u);
}

bool same_bytes(const Film& a, const Film& b) {
  return a.pixels().size() == b.pixels().size() &&
         std::memcmp(a.pixels().data(), b.pixels().data(), a.pixels().size() * sizeof(Color)) == 0;
}

// The project's rule (SPEC §6): the same bytes whatever the thread count, and a region's pixels
// (--crop, a distributed tile) the whole image's, under a filter wider than a pixel.
TEST(AccumulationBuffer, NeitherTheThreadsNorTheRegionChangeAPixel) {
  const HalfPlane edge(30, kWidth, kHeight);
  const auto scene = [&](double x, double y) {
    return edge(x, y) * Color(1, 0.5, 0.25) + Color(0.01 * x, 0.02 * y, 0);
  };
  for (AntialiasingSettings settings : {jittered(3), jittered_lattice(AntialiasingMode::adaptive, 2),
                                        jittered_lattice(AntialiasingMode::corners, 0)}) {
    for (const char* filter : {"box", "gaussian", "mitchell"}) {
      settings.filter = filter;
      Accumulated one, two;
      {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
        one = accumulate(settings, scene);
      }
      {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
        two = accumulate(settings, scene);
      }
      EXPECT_TRUE(same_bytes(one.film, two.film)) << filter;
      const Accumulated part = accumulate(settings, scene, SamplingRegion{5, 4, kWidth, kHeight}, 7, 5);
      for (int y = 0; y < 5; ++y)
        for (int x = 0; x < 7; ++x) {
          const Color& whole = one.film.at(x + 5, y + 4);
          EXPECT_EQ(std::memcmp(&part.film.at(x, y), &whole, sizeof(Color)), 0)
              << filter << " " << x << "," << y;
        }
    }
  }
}

}  // namespace
}  // namespace candela::accumulation_buffer_test
