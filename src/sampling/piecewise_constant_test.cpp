// Piecewise-constant distributions (SPEC §12): discrete probabilities, continuous densities
// that match pdf() bit for bit, zero cells never drawn, frequencies that follow the weights.
#include "sampling/piecewise_constant.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "math/pcg32.h"

namespace candela {
namespace {

TEST(Distribution1D, DiscreteProbabilitiesAndRemapping) {
  const Distribution1D d({1, 0, 3, 0, 4});
  ASSERT_TRUE(d.can_sample());
  EXPECT_DOUBLE_EQ(d.sum(), 8);
  EXPECT_DOUBLE_EQ(d.integral(), 8.0 / 5);
  EXPECT_DOUBLE_EQ(d.discrete_probability(2), 3.0 / 8);
  EXPECT_EQ(d.discrete_probability(1), 0);
  std::vector<int> counts(5, 0);
  Pcg32 rng(1, 2);
  double remapped_sum = 0;
  const int n = 80000;
  for (int i = 0; i < n; ++i) {
    std::size_t index = 99;
    double probability = 0, remapped = -1;
    ASSERT_TRUE(d.sample_discrete(rng.next_double(), index, probability, &remapped));
    ASSERT_LT(index, 5u);
    EXPECT_EQ(probability, d.discrete_probability(index));
    ASSERT_GE(remapped, 0);
    ASSERT_LT(remapped, 1);
    remapped_sum += remapped;
    ++counts[index];
  }
  EXPECT_EQ(counts[1], 0);
  EXPECT_EQ(counts[3], 0);
  for (int i : {0, 2, 4}) EXPECT_NEAR(counts[i] / double(n), d.discrete_probability(i), 0.006) << i;
  EXPECT_NEAR(remapped_sum / n, 0.5, 0.005);
  // The ends of [0, 1) land on cells with weight.
  std::size_t index;
  double probability;
  ASSERT_TRUE(d.sample_discrete(0.0, index, probability));
  EXPECT_EQ(index, 0u);
  ASSERT_TRUE(d.sample_discrete(std::nextafter(1.0, 0.0), index, probability));
  EXPECT_EQ(index, 4u);
  ASSERT_TRUE(d.sample_discrete(1.0 / 8, index, probability));  // exactly on the 0|2 boundary
  EXPECT_EQ(index, 2u);
}

TEST(Distribution1D, ContinuousDensityMatchesPdfAndIntegratesToOne) {
  const Distribution1D d({0.5, 2, 0, 1.5});
  Pcg32 rng(3, 4);
  double mean_inverse = 0;
  const int n = 40000;
  for (int i = 0; i < n; ++i) {
    double x = -1, pdf = 0;
    std::size_t cell = 9;
    ASSERT_TRUE(d.sample_continuous(rng.next_double(), x, pdf, &cell));
    ASSERT_GE(x, 0);
    ASSERT_LT(x, 1);
    EXPECT_EQ(pdf, d.pdf(x));
    EXPECT_EQ(cell, d.cell_of(x));
    EXPECT_NE(cell, 2u);
    mean_inverse += 1 / pdf;
  }
  // E[1/pdf] = the measure of the support, 3/4.
  EXPECT_NEAR(mean_inverse / n, 0.75, 0.01);
  EXPECT_DOUBLE_EQ(d.pdf(0.3), 2 / 1.0);  // weight 2 / integral 1
  EXPECT_EQ(d.pdf(0.6), 0);
  // Every boundary of a 3-cell table (whose edges are not representable) stays in its cell.
  const Distribution1D thirds({1, 1, 1});
  for (double u : {1.0 / 3, 2.0 / 3, std::nextafter(1.0 / 3, 0.0), std::nextafter(2.0 / 3, 1.0)}) {
    double x, pdf;
    std::size_t cell;
    ASSERT_TRUE(thirds.sample_continuous(u, x, pdf, &cell));
    EXPECT_EQ(thirds.cell_of(x), cell);
  }
}

TEST(Distribution1D, EmptyOrZeroCannotSample) {
  double x, pdf;
  std::size_t index;
  EXPECT_FALSE(Distribution1D(std::vector<double>{}).sample_continuous(0.5, x, pdf));
  EXPECT_FALSE(Distribution1D({0, 0}).sample_discrete(0.5, index, pdf));
  EXPECT_FALSE(Distribution1D({0, -1, std::nan("")}).can_sample());
  EXPECT_EQ(Distribution1D({0, 0}).pdf(0.5), 0);
}

TEST(Distribution2D, DensityMatchesPdfAndFollowsTheWeights) {
  // 3 columns × 2 rows.
  const std::vector<double> weights{1, 0, 2, 0, 0, 3};
  const Distribution2D d(weights, 3, 2);
  ASSERT_TRUE(d.can_sample());
  EXPECT_DOUBLE_EQ(d.integral(), 6.0 / 6);
  Pcg32 rng(5, 6);
  std::vector<int> counts(6, 0);
  const int n = 60000;
  for (int i = 0; i < n; ++i) {
    Vec2 p;
    double pdf = 0;
    ASSERT_TRUE(d.sample_continuous({rng.next_double(), rng.next_double()}, p, pdf));
    EXPECT_EQ(pdf, d.pdf(p));
    const int column = std::min(2, int(p.x * 3)), row = std::min(1, int(p.y * 2));
    EXPECT_DOUBLE_EQ(pdf, weights[row * 3 + column] / d.integral());
    ++counts[row * 3 + column];
  }
  for (int c = 0; c < 6; ++c) EXPECT_NEAR(counts[c] / double(n), weights[c] / 6, 0.006) << c;
  EXPECT_THROW(Distribution2D(weights, 4, 2), std::invalid_argument);
}

}  // namespace
}  // namespace candela
