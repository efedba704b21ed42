#include "camera/antialiasing.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <mutex>
#include <set>
#include <string>
#include <utility>

#include "half_plane.h"
#include "math/pcg32.h"

namespace candela {
namespace {

constexpr int kWidth = 16, kHeight = 12;

using testing::HalfPlane;

struct Render {
  Film film{kWidth, kHeight};
  SamplingResult result;
  std::vector<std::pair<double, double>> points;  // every radiance call
};

template <typename Radiance>
Render render(const AntialiasingSettings& settings, const Radiance& scene, int tile = 4, uint64_t seed = 7) {
  Render out;
  std::mutex mutex;
  const RadianceFunction radiance = [&](double x, double y) {
    {
      std::lock_guard lock(mutex);
      out.points.emplace_back(x, y);
    }
    return scene(x, y);
  };
  out.result = sample_image(settings, seed, {0, 0, kWidth, kHeight}, tile, radiance, out.film);
  return out;
}

AntialiasingSettings with_mode(AntialiasingMode mode, int n = 2) {
  AntialiasingSettings settings;
  settings.mode = mode;
  settings.n = n;
  return settings;
}

uint64_t sum(const std::vector<uint32_t>& counts) {
  uint64_t total = 0;
  for (const uint32_t c : counts) total += c;
  return total;
}

std::size_t unique_points(std::vector<std::pair<double, double>> points) {
  std::sort(points.begin(), points.end());
  return std::size_t(std::unique(points.begin(), points.end()) - points.begin());
}

// The adaptive cache's buckets come from the low bits of the hash: the keys of a 256 × 256
// lattice must spread over them like random numbers (about 63 % of 2¹⁶ buckets for 2¹⁶ keys),
// not collapse onto one bucket per column as TBB's identity hash of the key did.
TEST(Antialiasing, LatticeKeysSpreadOverHashBuckets) {
  std::vector<bool> bucket_used(1 << 16, false);
  for (uint64_t iy = 0; iy < 256; ++iy)
    for (uint64_t ix = 0; ix < 256; ++ix) bucket_used[lattice_key_hash(iy << 32 | ix) & 0xffff] = true;
  const auto used = std::count(bucket_used.begin(), bucket_used.end(), true);
  EXPECT_GT(used, 0.6 * (1 << 16));
  EXPECT_LT(used, 0.66 * (1 << 16));
}

TEST(Antialiasing, ModeNamesRoundTrip) {
  for (const auto name : {"none", "uniform", "jittered", "corners", "adaptive"}) {
    AntialiasingMode mode;
    ASSERT_TRUE(kAntialiasingModeNames.value(name));
    mode = *kAntialiasingModeNames.value(name);
    EXPECT_EQ(kAntialiasingModeNames.name(mode), name);
  }
  EXPECT_FALSE(kAntialiasingModeNames.value("supersampled"));
}

TEST(Antialiasing, NoneTracesThePixelCentres) {
  const Render r = render(with_mode(AntialiasingMode::none), HalfPlane(30, kWidth, kHeight));
  EXPECT_EQ(r.result.traced, uint64_t(kWidth * kHeight));
  for (const auto& [x, y] : r.points) {
    EXPECT_EQ(x - std::floor(x), 0.5);
    EXPECT_EQ(y - std::floor(y), 0.5);
  }
}

TEST(Antialiasing, CornersCostsOneRayPerLatticePoint) {
  const Render r = render(with_mode(AntialiasingMode::corners), HalfPlane(30, kWidth, kHeight));
  EXPECT_EQ(r.result.traced, uint64_t((kWidth + 1) * (kHeight + 1)));
  EXPECT_EQ(r.points.size(), std::size_t((kWidth + 1) * (kHeight + 1)));
  EXPECT_EQ(unique_points(r.points), r.points.size());
  EXPECT_EQ(sum(r.result.traced_per_pixel), r.result.traced);
  EXPECT_EQ(*std::max_element(r.result.samples_per_pixel.begin(), r.result.samples_per_pixel.end()), 4u);
}

TEST(Antialiasing, AdaptiveNeverTracesAPointTwice) {
  for (const bool jitter : {false, true}) {
    AntialiasingSettings settings = with_mode(AntialiasingMode::adaptive);
    settings.max_level = 3;
    settings.jitter = jitter;
    const Render r = render(settings, HalfPlane(30, kWidth, kHeight), 3);
    EXPECT_EQ(r.result.traced, r.points.size());
    EXPECT_EQ(unique_points(r.points), r.points.size()) << "jitter " << jitter;
    EXPECT_EQ(sum(r.result.traced_per_pixel), r.result.traced);
    EXPECT_GT(r.result.traced, uint64_t((kWidth + 1) * (kHeight + 1)));
  }
}

TEST(Antialiasing, AFlatImageTriggersNoSubdivision) {
  AntialiasingSettings settings = with_mode(AntialiasingMode::adaptive);
  settings.max_level = 4;
  const Render r = render(settings, [](double, double) { return Color(0.3, 0.7, 0.1); });
  EXPECT_EQ(r.result.traced, uint64_t((kWidth + 1) * (kHeight + 1)));
  for (const Color& c : r.film.pixels()) EXPECT_EQ(c, Color(0.3, 0.7, 0.1));
}

TEST(Antialiasing, ContrastThresholdsArePerChannel) {
  // A blue-only step of contrast 1/3: below B's 0.4, so no subdivision; above with 0.3.
  const auto step = [](double x, double) { return Color(0.5, 0.5, x < kWidth / 2.0 + 0.3 ? 0.5 : 1.0); };
  AntialiasingSettings settings = with_mode(AntialiasingMode::adaptive);
  EXPECT_EQ(render(settings, step).result.traced, uint64_t((kWidth + 1) * (kHeight + 1)));
  settings.threshold.b = 0.3;
  EXPECT_GT(render(settings, step).result.traced, uint64_t((kWidth + 1) * (kHeight + 1)));
}

// Worst |pixel − exact white area| over the image for one edge.
double worst_error(const Film& film, const HalfPlane& edge) {
  double worst = 0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) worst = std::max(worst, std::fabs(film.at(x, y).r - edge.covered(x, y)));
  return worst;
}

TEST(Antialiasing, HalfPlaneEdgeErrorShrinksWithN) {
  for (const double degrees : {10.0, 30.0, 45.0, 80.0}) {
    const HalfPlane edge(degrees, kWidth, kHeight);
    for (const AntialiasingMode mode : {AntialiasingMode::uniform, AntialiasingMode::jittered}) {
      for (const int n : {1, 2, 4, 8}) {
        const Render r = render(with_mode(mode, n), edge);
        EXPECT_EQ(r.result.traced, uint64_t(kWidth * kHeight * n * n));
        const double error = worst_error(r.film, edge);
        // Jittered: at most the 2n − 1 sub-cells the edge crosses are wrong, each by 1/n²;
        // uniform centres do better: within 1/n.
        const double bound = mode == AntialiasingMode::uniform ? 1.0 / n : (2.0 * n - 1) / (n * n);
        EXPECT_LE(error, bound + 1e-9)
            << std::string(kAntialiasingModeNames.name(mode)) << " n=" << n << " at " << degrees << "°";
        std::printf("  %-8s n=%d at %4.0f°: worst pixel error %.4f\n",
                    std::string(kAntialiasingModeNames.name(mode)).c_str(), n, degrees, error);
      }
    }
    const double corners = worst_error(render(with_mode(AntialiasingMode::corners), edge).film, edge);
    EXPECT_LE(corners, 0.75 + 1e-9);
  }
}

TEST(Antialiasing, AdaptiveMatchesTheDenseLatticeOnEdgePixelsWithFewerRays) {
  constexpr int kLevel = 3, kScale = 1 << kLevel;
  for (const double degrees : {10.0, 30.0, 45.0, 80.0}) {
    const HalfPlane edge(degrees, kWidth, kHeight);
    AntialiasingSettings settings = with_mode(AntialiasingMode::adaptive);
    settings.max_level = kLevel;
    const Render adaptive = render(settings, edge);
    AntialiasingSettings uniform_settings = with_mode(AntialiasingMode::uniform);
    uniform_settings.n = kScale;
    const Render uniform = render(uniform_settings, edge);  // uniform 2^L × 2^L sub-pixel centres
    double worst_uniform = 0;
    // The dense 2^L × 2^L corner lattice: each pixel the mean of its 64 sub-squares' corner means.
    const uint64_t dense_rays = uint64_t(kWidth * kScale + 1) * (kHeight * kScale + 1);
    double worst = 0, worst_exact = 0;
    for (int y = 0; y < kHeight; ++y) {
      for (int x = 0; x < kWidth; ++x) {
        const double exact = edge.covered(x, y);
        if (exact <= 0 || exact >= 1) continue;  // edge pixels only
        double dense = 0;
        for (int j = 0; j < kScale; ++j)
          for (int i = 0; i < kScale; ++i) {
            const auto at = [&](int a, int b) {
              return edge(x + double(i + a) / kScale, y + double(j + b) / kScale).r;
            };
            dense += (at(0, 0) + at(1, 0) + at(0, 1) + at(1, 1)) / 4;
          }
        dense /= kScale * kScale;
        worst = std::max(worst, std::fabs(adaptive.film.at(x, y).r - dense));
        worst_exact = std::max(worst_exact, std::fabs(adaptive.film.at(x, y).r - exact));
        worst_uniform =
            std::max(worst_uniform, std::fabs(adaptive.film.at(x, y).r - uniform.film.at(x, y).r));
      }
    }
    EXPECT_LT(worst, 1e-12) << degrees << "°";
    EXPECT_LE(worst_exact, 2.0 / kScale) << degrees << "°";
    EXPECT_LT(adaptive.result.traced, dense_rays);
    // Uniform 2^L × 2^L estimates the same covered area (both within 1/2^L of it on an edge):
    // adaptive matches it to that accuracy with fewer rays over the image.
    EXPECT_LE(worst_uniform, 2.0 / kScale) << degrees << "°";
    EXPECT_LT(adaptive.result.traced, uniform.result.traced);
    // The uniform 8×8 sub-pixel centres cost this many rays.
    const uint64_t uniform_rays = uint64_t(kWidth * kHeight) * kScale * kScale;
    std::printf(
        "  adaptive L=%d at %4.0f°: %llu rays vs %llu for the dense lattice (ratio %.3f) and %llu for "
        "uniform %dx%d; worst edge-pixel error vs exact area %.4f\n",
        kLevel, degrees, static_cast<unsigned long long>(adaptive.result.traced),
        static_cast<unsigned long long>(dense_rays), double(adaptive.result.traced) / double(dense_rays),
        static_cast<unsigned long long>(uniform_rays), kScale, kScale, worst_exact);
  }
}

TEST(Antialiasing, SeedExampleOnePixelTwoLevels) {
  // As in 001's worked example: one pixel, three leaf quadrants at level 1 and the fourth split
  // into four leaves at level 2; pixel = ¼(Q1 + Q2 + Q3 + ¼(L1 + L2 + L3 + L4)).
  AntialiasingSettings settings = with_mode(AntialiasingMode::adaptive);
  settings.max_level = 2;
  Film film(1, 1);
  std::vector<std::pair<double, double>> points;
  const RadianceFunction radiance = [&](double x, double y) {
    points.emplace_back(x, y);
    return Color(x > 0.6 && y > 0.6 ? 1.0 : 0.0);
  };
  const SamplingResult r = sample_image(settings, 0, {0, 0, 1, 1}, 1, radiance, film);
  // Level 0: 4 corners (1 white); level 1: 5 midpoints; the bottom-right quadrant splits (5 more),
  // and of its children only the bottom-right one is all white at level 2.
  EXPECT_EQ(r.traced, 4u + 5u + 5u);
  EXPECT_EQ(r.samples_per_pixel[0], 14u);
  // Samples at x, y in {0.75, 1} are white: leaf TL of the quadrant (0.5..0.75) has one white
  // corner (0.75, 0.75); TR and BL two white corners each; BR four.
  const double expected = (0 + 0 + 0 + (0.25 + 0.5 + 0.5 + 1.0) / 4) / 4;
  EXPECT_DOUBLE_EQ(film.at(0, 0).r, expected);
}

TEST(Antialiasing, ImagesDoNotDependOnTheThreadCount) {
  std::vector<AntialiasingSettings> all;
  for (const AntialiasingMode mode :
       {AntialiasingMode::none, AntialiasingMode::uniform, AntialiasingMode::jittered,
        AntialiasingMode::corners, AntialiasingMode::adaptive})
    all.push_back(with_mode(mode, 3));
  all.push_back(with_mode(AntialiasingMode::adaptive));
  all.back().jitter = true;
  all.back().max_level = 3;
  all.push_back(with_mode(AntialiasingMode::jittered, 4));
  all.back().filter = "mitchell";
  all.push_back(with_mode(AntialiasingMode::uniform, 4));
  all.back().filter = "gaussian";
  // A radiance with texture everywhere so adaptive subdivides unevenly.
  const auto scene = [](double x, double y) {
    return Color(0.5 + 0.5 * std::sin(x * 1.7) * std::cos(y * 2.3), x * y > 40 ? 1.0 : 0.1, 0.3);
  };
  for (const AntialiasingSettings& settings : all) {
    Render one, two;
    {
      tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
      one = render(settings, scene, 2);
    }
    {
      tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
      two = render(settings, scene, 2);
    }
    const std::string mode = std::string(kAntialiasingModeNames.name(settings.mode));
    ASSERT_EQ(one.film.pixels().size(), two.film.pixels().size());
    EXPECT_EQ(std::memcmp(one.film.pixels().data(), two.film.pixels().data(),
                          one.film.pixels().size() * sizeof(Color)),
              0)
        << mode;
    EXPECT_EQ(one.result.traced, two.result.traced) << mode;
    EXPECT_EQ(one.result.traced_per_pixel, two.result.traced_per_pixel) << mode;
    EXPECT_EQ(one.result.samples_per_pixel, two.result.samples_per_pixel) << mode;
  }
}

// Every mode with and without lattice jitter, for the tests that go over all of them.
std::vector<AntialiasingSettings> every_mode() {
  std::vector<AntialiasingSettings> all;
  for (const AntialiasingMode mode :
       {AntialiasingMode::none, AntialiasingMode::uniform, AntialiasingMode::jittered,
        AntialiasingMode::corners, AntialiasingMode::adaptive})
    all.push_back(with_mode(mode, 3));
  for (const AntialiasingMode mode : {AntialiasingMode::corners, AntialiasingMode::adaptive}) {
    all.push_back(with_mode(mode));
    all.back().jitter = true;
    all.back().max_level = 3;
  }
  return all;
}

std::string describe(const AntialiasingSettings& settings) {
  return std::string(kAntialiasingModeNames.name(settings.mode)) + (settings.jitter ? "+jitter" : "") + " " +
         settings.filter;
}

// The box of radius 0.5 is each pixel's mean of its own samples, summed in the order they are
// taken: the images of before reconstruction filters splatted across pixels, bit for bit.
TEST(Antialiasing, BoxOfHalfAPixelIsTheMeanOfEachPixelsOwnSamples) {
  const auto scene = [](double x, double y) {
    return Color(0.5 + 0.5 * std::sin(x * 1.7) * std::cos(y * 2.3), x * y > 40 ? 1.0 : 0.1, 0.3);
  };
  for (const AntialiasingMode mode : {AntialiasingMode::uniform, AntialiasingMode::jittered}) {
    for (const int n : {1, 3}) {
      const Render r = render(with_mode(mode, n), scene, 5);
      for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) {
          Pcg32 rng = pixel_rng(7, static_cast<uint32_t>(x), static_cast<uint32_t>(y));
          Color sum;
          double weight = 0;
          for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
              const double u = mode == AntialiasingMode::jittered ? rng.next_double() : 0.5;
              const double v = mode == AntialiasingMode::jittered ? rng.next_double() : 0.5;
              sum += scene(x + (i + u) / n, y + (j + v) / n) * 1.0;
              weight += 1.0;
            }
          const Color expected = sum / weight;
          ASSERT_EQ(std::memcmp(&r.film.at(x, y), &expected, sizeof(Color)), 0)
              << kAntialiasingModeNames.name(mode) << " n=" << n << " pixel " << x << "," << y;
        }
    }
  }
  const Render none = render(with_mode(AntialiasingMode::none), scene);
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) EXPECT_EQ(none.film.at(x, y), scene(x + 0.5, y + 0.5));
}

// A real reconstruction filter: a bright line one pixel wide (column 7) stays
// in the columns its samples fall in under the box, and spreads by exactly the filter's reach
// (the pixels whose centres lie within the radius of a sample) under wider filters.
TEST(Antialiasing, AOnePixelLineWidensByTheFilterRadiusAndStaysPutUnderTheBox) {
  constexpr int kColumn = 7;
  const auto line = [](double x, double) { return Color(x >= kColumn && x < kColumn + 1 ? 1.0 : 0.0); };
  // The columns holding any light, for each row alike.
  const auto lit_columns = [](const Film& film) {
    std::set<int> columns;
    for (int y = 0; y < kHeight; ++y)
      for (int x = 0; x < kWidth; ++x)
        if (film.at(x, y).r != 0) columns.insert(x);
    return columns;
  };
  for (AntialiasingSettings settings : every_mode()) {
    const std::set<int> boxed = lit_columns(render(settings, line).film);
    ASSERT_FALSE(boxed.empty()) << describe(settings);
    const bool point_samples = settings.mode == AntialiasingMode::none ||
                               settings.mode == AntialiasingMode::uniform ||
                               settings.mode == AntialiasingMode::jittered;
    if (point_samples) {
      // Point samples inside the column: the box keeps the line in its column, at full strength.
      EXPECT_EQ(boxed, std::set<int>{kColumn}) << describe(settings);
      const Render r = render(settings, line);
      for (int y = 0; y < kHeight; ++y) EXPECT_EQ(r.film.at(kColumn, y).r, 1.0) << describe(settings);
    }
    for (const auto& [radius, reach] : {std::pair{1.5, 1}, std::pair{2.5, 2}, std::pair{2.2, 2}}) {
      settings.filter = "gaussian";
      settings.filter_parameters = {radius, 0};
      const Render r = render(settings, line);
      const auto widened = [&](int by) {
        std::set<int> columns;
        for (const int column : boxed)
          for (int k = -by; k <= by; ++k) columns.insert(column + k);
        return columns;
      };
      const std::set<int> lit = lit_columns(r.film);
      if (point_samples) {
        // Every sample lies in [7, 8): it reaches the pixels whose centres are within the radius.
        EXPECT_EQ(lit, widened(reach)) << describe(settings) << " radius " << radius;
      } else {
        // A leaf square is splatted from its centre, somewhere inside its pixel: at least one pixel
        // farther each side than the box, never past the reach.
        const std::set<int> least = widened(1), most = widened(reach);
        EXPECT_TRUE(std::includes(lit.begin(), lit.end(), least.begin(), least.end()))
            << describe(settings) << " radius " << radius;
        EXPECT_TRUE(std::includes(most.begin(), most.end(), lit.begin(), lit.end()))
            << describe(settings) << " radius " << radius;
      }
      // Spread, not copied: the line's own column loses light to its neighbours, which get less
      // the farther they are.
      for (int y = 0; y < kHeight; ++y) {
        EXPECT_LT(r.film.at(kColumn, y).r, 1.0) << describe(settings);
        EXPECT_GT(r.film.at(kColumn + 1, y).r, r.film.at(kColumn + reach + 1, y).r) << describe(settings);
      }
    }
    settings.filter_parameters = {};
  }
}

TEST(Antialiasing, EveryFilterAndModeIsThreadIndependentAndCropsKeepThePixels) {
  const auto scene = [](double x, double y) {
    return Color(0.5 + 0.5 * std::sin(x * 1.7) * std::cos(y * 2.3), x * y > 40 ? 1.0 : 0.1,
                 (int(x) + int(y)) % 3 == 0 ? 0.9 : 0.2);
  };
  for (const PixelFilterEntry& filter : pixel_filter_entries()) {
    for (AntialiasingSettings settings : every_mode()) {
      settings.filter = filter.name;
      Render one, two;
      {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
        one = render(settings, scene, 3);
      }
      {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
        two = render(settings, scene, 3);
      }
      EXPECT_EQ(std::memcmp(one.film.pixels().data(), two.film.pixels().data(),
                            one.film.pixels().size() * sizeof(Color)),
                0)
          << describe(settings);
      EXPECT_EQ(one.result.traced_per_pixel, two.result.traced_per_pixel) << describe(settings);
      EXPECT_EQ(one.result.samples_per_pixel, two.result.samples_per_pixel) << describe(settings);
      // A region (a distributed tile, --crop) samples the ring its filter reaches: its pixels are
      // the whole image's, bit for bit.
      Film part(7, 5);
      const RadianceFunction radiance = [&](double x, double y) { return scene(x, y); };
      sample_image(settings, 7, {5, 4, kWidth, kHeight}, 3, radiance, part);
      for (int y = 0; y < part.height(); ++y)
        for (int x = 0; x < part.width(); ++x)
          ASSERT_EQ(std::memcmp(&part.at(x, y), &one.film.at(x + 5, y + 4), sizeof(Color)), 0)
              << describe(settings) << " pixel " << x + 5 << "," << y + 4;
    }
  }
}

TEST(Antialiasing, AdaptiveSamplesAreReconstructedWithTheFilter) {
  // Before, aa.filter was ignored by adaptive: now a wider filter changes the image.
  AntialiasingSettings settings = with_mode(AntialiasingMode::adaptive);
  settings.max_level = 3;
  const HalfPlane edge(30, kWidth, kHeight);
  const Render boxed = render(settings, edge);
  settings.filter = "gaussian";
  const Render smooth = render(settings, edge);
  EXPECT_EQ(boxed.result.traced, smooth.result.traced);  // the same samples
  double largest = 0;
  for (std::size_t i = 0; i < boxed.film.pixels().size(); ++i)
    largest = std::max(largest, std::fabs(boxed.film.pixels()[i].r - smooth.film.pixels()[i].r));
  EXPECT_GT(largest, 0.1);
}

TEST(Antialiasing, ACroppedRegionKeepsThePixelValues) {
  AntialiasingSettings settings = with_mode(AntialiasingMode::adaptive);
  settings.max_level = 3;
  settings.jitter = true;
  const HalfPlane edge(30, kWidth, kHeight);
  const Render full = render(settings, edge);
  Film part(5, 4);
  const RadianceFunction radiance = [&](double x, double y) { return edge(x, y); };
  sample_image(settings, 7, {3, 2, kWidth, kHeight}, 4, radiance, part);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 5; ++x) EXPECT_EQ(part.at(x, y), full.film.at(x + 3, y + 2));
}

}  // namespace
}  // namespace candela
