#include "radiosity/diagnostics.h"

#include <gtest/gtest.h>

#include <vector>

namespace candela {
namespace {

TEST(RadiosityDiagnostics, RowSumsCountHiddenRowsApart) {
  // Rows that see nothing (below kHiddenRowSum) are hidden, not open: they stay out of the
  // minimum and the mean.
  const nlohmann::json facts = row_sum_facts({1.0, 0.98, 0.0, 0.5 * kHiddenRowSum, 1.02});
  EXPECT_EQ(facts["rows"], 3);
  EXPECT_EQ(facts["hidden_rows"], 2);
  EXPECT_DOUBLE_EQ(facts["min"].get<double>(), 0.98);
  EXPECT_DOUBLE_EQ(facts["max"].get<double>(), 1.02);
  EXPECT_NEAR(facts["mean"].get<double>(), 1.0, 1e-15);
  // Nothing but hidden rows: no min, mean or max.
  const nlohmann::json hidden = row_sum_facts({0.0, 0.0});
  EXPECT_EQ(hidden["rows"], 0);
  EXPECT_EQ(hidden["hidden_rows"], 2);
  EXPECT_FALSE(hidden.contains("min"));
  EXPECT_FALSE(hidden.contains("mean"));
}

TEST(RadiosityDiagnostics, ReciprocityIsTheTransferWeightedMismatch) {
  // 000 eq. 6-5: A_1 F_12 = A_2 F_21. Areas 1 and 2, F_12 = 0.4: reciprocal with F_21 = 0.2.
  std::vector<RadiositySurface> patches(2);
  patches[0].area = 1;
  patches[1].area = 2;
  Eigen::MatrixXd rows(2, 2);
  rows << 0, 0.4, 0.2, 0;
  const Reciprocity exact = measure_reciprocity(patches, rows);
  EXPECT_TRUE(exact.measured);
  EXPECT_EQ(exact.mean_error, 0);
  EXPECT_EQ(exact.max_error, 0);
  // F_21 = 0.25: transfers 0.4 and 0.5, mismatch 0.1 of 0.9 in all and of the largest 0.5.
  rows(1, 0) = 0.25;
  const Reciprocity off = measure_reciprocity(patches, rows);
  EXPECT_NEAR(off.mean_error, 0.1 / 0.9, 1e-15);
  EXPECT_NEAR(off.max_error, 0.1 / 0.5, 1e-15);
  // Nothing transferred: no error.
  const Reciprocity dark = measure_reciprocity(patches, Eigen::MatrixXd::Zero(2, 2));
  EXPECT_EQ(dark.mean_error, 0);
  EXPECT_EQ(dark.max_error, 0);
}

}  // namespace
}  // namespace candela
