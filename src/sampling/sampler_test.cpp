// The samplers against their definitions (the Sobol' digits, nets and strata),
// uniformity (χ² of 2D projections, within a sample and across its dimensions), the error on a
// smooth integrand falling faster than N^-1/2 for the low-discrepancy sampler, and determinism.
#include "sampling/sampler.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <numeric>
#include <set>
#include <stdexcept>
#include <vector>

#include "sampling/independent_sampler.h"
#include "sampling/sobol_sampler.h"
#include "sampling/stratified_sampler.h"

namespace candela {
namespace {

// Dimension 0: van der Corput. Dimension 1: direction numbers m = 1, 3, 5, 15 (v_k = m_k / 2^k,
// Joe and Kuo's second dimension), the point of index i the xor of v_k over the bits k of i.
TEST(Sobol, FirstDimensionsAreTheKnownSequences) {
  const double dimension_0[] = {0, 0.5, 0.25, 0.75, 0.125, 0.625, 0.375, 0.875};
  const double dimension_1[] = {0, 0.5, 0.75, 0.25, 0.625, 0.125, 0.375, 0.875};
  for (uint32_t i = 0; i < 8; ++i) {
    EXPECT_EQ(sobol_dimension_0(i) * 0x1p-32, dimension_0[i]) << i;
    EXPECT_EQ(sobol_dimension_1(i) * 0x1p-32, dimension_1[i]) << i;
  }
  EXPECT_EQ(sobol_dimension_1(8), 15u << 28);  // v₄ = 15/16
  EXPECT_EQ(reverse_bits(1), 0x80000000u);
  EXPECT_EQ(reverse_bits(0x12345678u), 0x1e6a2c48u);
}

// Owen's scrambling maps each aligned interval of 2^-k to an aligned interval of 2^-k: two
// fractions that share their first k bits still do after it, and it is a bijection.
TEST(Sobol, NestedUniformScramblingKeepsLeadingDigitsTogether) {
  for (const uint32_t seed : {1u, 0xdeadbeefu, 12345u})
    for (uint32_t a = 0; a < 2000; ++a) {
      const uint32_t x = a * 0x9e3779b9u, y = x ^ (a % 31 == 0 ? 1u : (a & 0xffffu));
      const int shared = std::countl_zero(x ^ y);
      const uint32_t sx = nested_uniform_scramble(x, seed), sy = nested_uniform_scramble(y, seed);
      const int kept = std::countl_zero(sx ^ sy);
      EXPECT_EQ(kept, shared) << x << " " << y;
    }
}

// Every elementary interval of area 2^-m (2^a × 2^(m−a) cells, each a) holds exactly one of the
// points: a (0, m, 2)-net in base 2.
void expect_net(const std::vector<Vec2>& points, int m) {
  for (int a = 0; a <= m; ++a) {
    const int columns = 1 << a, rows = 1 << (m - a);
    std::vector<int> count(std::size_t(columns) * rows, 0);
    for (const Vec2& p : points) ++count[std::size_t(p.y * rows) * columns + std::size_t(p.x * columns)];
    for (std::size_t c = 0; c < count.size(); ++c)
      ASSERT_EQ(count[c], 1) << "m " << m << " a " << a << " cell " << c;
  }
}

TEST(SobolSampler, TheFirstPowerOfTwoPassesOfAPixelAreANetInEveryDimension) {
  SobolSampler sampler(7);
  for (const int m : {2, 4, 6, 8, 10}) {
    SCOPED_TRACE(m);
    const uint32_t n = 1u << m;
    std::vector<std::vector<Vec2>> pairs(4);
    std::vector<std::vector<double>> singles(2);
    for (uint32_t pass = 0; pass < n; ++pass) {
      sampler.start_pixel_sample(3, 5, pass);
      pairs[0].push_back(sampler.get_2d());
      singles[0].push_back(sampler.get_1d());
      pairs[1].push_back(sampler.get_2d());
      singles[1].push_back(sampler.get_1d());
      pairs[2].push_back(sampler.get_2d());
      for (int skip = 0; skip < 9; ++skip) sampler.get_1d();
      pairs[3].push_back(sampler.get_2d());
    }
    for (const auto& points : pairs) expect_net(points, m);
    for (auto& values : singles) {
      std::vector<int> count(n, 0);
      for (const double v : values) ++count[std::size_t(v * n)];
      EXPECT_EQ(*std::min_element(count.begin(), count.end()), 1);
      EXPECT_EQ(*std::max_element(count.begin(), count.end()), 1);
    }
  }
}

TEST(StratifiedSampler, ThePassesOfAPixelTakeEveryStratumOnce) {
  for (const uint32_t n : {1u, 10u, 16u, 37u, 64u}) {
    SCOPED_TRACE(n);
    StratifiedSampler sampler(11, n);
    const uint32_t columns = static_cast<uint32_t>(std::ceil(std::sqrt(double(n))));
    const uint32_t rows = (n + columns - 1) / columns;
    std::vector<int> strata(n, 0), later(n, 0), cells(columns * rows, 0);
    for (uint32_t pass = 0; pass < n; ++pass) {
      sampler.start_pixel_sample(9, 2, pass);
      const Vec2 p = sampler.get_2d();
      ++cells[std::size_t(p.y * rows) * columns + std::size_t(p.x * columns)];
      ++strata[std::size_t(sampler.get_1d() * n)];
      sampler.get_2d();
      ++later[std::size_t(sampler.get_1d() * n)];
    }
    for (uint32_t s = 0; s < n; ++s) EXPECT_EQ(strata[s], 1) << s;
    for (uint32_t s = 0; s < n; ++s) EXPECT_EQ(later[s], 1) << s;
    EXPECT_LE(*std::max_element(cells.begin(), cells.end()), 1);
  }
}

TEST(StratifiedSampler, PermutationElementIsAPermutationForEverySizeAndSeed) {
  for (uint32_t n = 1; n <= 300; ++n)
    for (const uint32_t seed : {0u, 1u, 0x12345678u, 0xffffffffu}) {
      std::vector<bool> seen(n, false);
      for (uint32_t i = 0; i < n; ++i) {
        const uint32_t e = permutation_element(i, n, seed);
        ASSERT_LT(e, n);
        ASSERT_FALSE(seen[e]) << n << " " << seed << " " << i;
        seen[e] = true;
      }
    }
  // Different seeds give different orders.
  int same = 0;
  for (uint32_t i = 0; i < 64; ++i) same += permutation_element(i, 64, 1) == permutation_element(i, 64, 2);
  EXPECT_LT(same, 16);
}

std::unique_ptr<Sampler> make(const char* name, uint64_t samples) {
  return create_sampler(name, SamplerParameters{42, samples});
}

// χ² of n points in 8 × 8 bins against uniform (63 degrees of freedom: the 10⁻⁶ quantile is 128).
double chi_square(const std::vector<Vec2>& points) {
  std::vector<double> count(64, 0);
  for (const Vec2& p : points) {
    EXPECT_TRUE(p.x >= 0 && p.x < 1 && p.y >= 0 && p.y < 1) << p.x << " " << p.y;
    ++count[std::size_t(p.y * 8) * 8 + std::size_t(p.x * 8)];
  }
  const double expected = double(points.size()) / 64;
  double chi2 = 0;
  for (const double c : count) chi2 += (c - expected) * (c - expected) / expected;
  return chi2;
}

// The 2D projections of every sampler are uniform: a pair of one sample, and values of different
// dimensions paired (the padding must not correlate them), over 32 passes of 256 pixels.
TEST(Samplers, TwoDimensionalProjectionsAreUniform) {
  for (const SamplerEntry& entry : sampler_entries()) {
    SCOPED_TRACE(entry.name);
    const auto sampler = make(entry.name, 32);
    std::vector<Vec2> pixel, light, across_1d, across_2d;
    for (uint32_t y = 0; y < 16; ++y)
      for (uint32_t x = 0; x < 16; ++x)
        for (uint32_t pass = 0; pass < 32; ++pass) {
          sampler->start_pixel_sample(x, y, pass);
          pixel.push_back(sampler->get_2d());
          const double choice = sampler->get_1d();
          light.push_back(sampler->get_2d());
          const double lobe = sampler->get_1d();
          const Vec2 direction = sampler->get_2d();
          across_1d.push_back({choice, lobe});
          across_2d.push_back({pixel.back().x, direction.y});
        }
    for (const auto* points : {&pixel, &light, &across_1d, &across_2d}) EXPECT_LT(chi_square(*points), 128);
  }
}

// ∫∫ f over the unit square by N passes of one pixel, the RMS error over 128 pixels, for a smooth
// f that is not a sum of functions of x and of y.
double rms_error(Sampler& sampler, uint32_t n) {
  const auto f = [](const Vec2& p) { return std::exp(p.x) * std::sin(1 + p.y) + p.x * p.y; };
  const double exact = (std::exp(1.0) - 1) * (std::cos(1.0) - std::cos(2.0)) + 0.25;
  double squares = 0;
  for (uint32_t pixel = 0; pixel < 128; ++pixel) {
    double sum = 0;
    for (uint32_t pass = 0; pass < n; ++pass) {
      sampler.start_pixel_sample(pixel, 1, pass);
      sampler.get_2d();
      sampler.get_1d();
      sum += f(sampler.get_2d());  // a later dimension, as the light's point of the first bounce
    }
    squares += (sum / n - exact) * (sum / n - exact);
  }
  return std::sqrt(squares / 128);
}

// The slope of log error against log N from 16 to 1024 samples: −1/2 for independent numbers;
// Owen-scrambled Sobol' does much better on a smooth integrand (about −1.5 in theory); strata of
// one sample each give about −1 in 2D.
TEST(Samplers, ErrorOnASmoothIntegrandFallsFasterThanTheSquareRootForSobol) {
  const auto slope = [](const char* name) {
    const double low = rms_error(*make(name, 16), 16);
    const double high = rms_error(*make(name, 1024), 1024);
    return std::log(high / low) / std::log(1024.0 / 16.0);
  };
  const double independent = slope("independent"), stratified = slope("stratified"), sobol = slope("sobol");
  EXPECT_NEAR(independent, -0.5, 0.12);
  EXPECT_LT(stratified, -0.8);
  EXPECT_LT(sobol, -1.1);
  EXPECT_LT(rms_error(*make("sobol", 256), 256), 0.1 * rms_error(*make("independent", 256), 256));
}

TEST(Samplers, ASampleIsAPureFunctionOfSeedPixelPassAndDimension) {
  for (const SamplerEntry& entry : sampler_entries()) {
    SCOPED_TRACE(entry.name);
    const auto a = make(entry.name, 64);
    const auto b = a->clone();
    EXPECT_EQ(b->name(), entry.name);
    std::vector<double> first;
    a->start_pixel_sample(5, 6, 7);
    for (int i = 0; i < 20; ++i) first.push_back(a->get_1d());
    // Other pixels and passes in between, on the clone and on the original.
    b->start_pixel_sample(6, 5, 7);
    b->get_2d();
    a->start_pixel_sample(5, 6, 8);
    a->get_1d();
    for (Sampler* s : {a.get(), b.get()}) {
      s->start_pixel_sample(5, 6, 7);
      for (int i = 0; i < 20; ++i) ASSERT_EQ(s->get_1d(), first[i]) << i;
    }
    // Another pixel, pass or seed gives other values.
    a->start_pixel_sample(6, 5, 7);
    EXPECT_NE(a->get_1d(), first[0]);
    a->start_pixel_sample(5, 6, 9);
    EXPECT_NE(a->get_1d(), first[0]);
    const auto other_seed = create_sampler(entry.name, SamplerParameters{43, 64});
    other_seed->start_pixel_sample(5, 6, 7);
    EXPECT_NE(other_seed->get_1d(), first[0]);
  }
}

// The independent sampler is the path tracer's stream from before samplers existed.
TEST(IndependentSampler, DrawsThePixelAndPassStream) {
  IndependentSampler sampler(42);
  sampler.start_pixel_sample(3, 4, 5);
  Pcg32 stream = independent_stream(42, 5, 3, 4);
  const Vec2 p = sampler.get_2d();
  EXPECT_EQ(p.x, stream.next_double());
  EXPECT_EQ(p.y, stream.next_double());
  EXPECT_EQ(sampler.get_1d(), stream.next_double());
}

TEST(SamplerRegistry, NamesAndRefusals) {
  EXPECT_EQ(sampler_names(), "independent, stratified, sobol");
  EXPECT_EQ(find_sampler("halton"), nullptr);
  try {
    create_sampler("halton", {});
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(
        std::string(e.what()).find("unknown sampler \"halton\" (known: independent, stratified, sobol)"),
        std::string::npos)
        << e.what();
  }
  EXPECT_THROW(create_sampler("stratified", SamplerParameters{1, 0}), std::invalid_argument);
  EXPECT_NO_THROW(create_sampler("sobol", SamplerParameters{1, 0}));
}

}  // namespace
}  // namespace candela
