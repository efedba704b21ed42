#include "radiosity/diagnostics.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

namespace candela {

nlohmann::json row_sum_facts(const std::vector<double>& row_sums) {
  double min = std::numeric_limits<double>::infinity(), max = 0, total = 0;
  std::size_t rows = 0, hidden_rows = 0;
  for (const double sum : row_sums) {
    if (sum < kHiddenRowSum) {
      ++hidden_rows;
      continue;
    }
    min = std::min(min, sum);
    max = std::max(max, sum);
    total += sum;
    ++rows;
  }
  nlohmann::json json = {{"rows", rows}, {"hidden_rows", hidden_rows}};
  if (rows > 0) {
    json["min"] = min;
    json["mean"] = total / static_cast<double>(rows);
    json["max"] = max;
  }
  return json;
}

Reciprocity measure_reciprocity(const std::vector<RadiositySurface>& patches,
                                const Eigen::MatrixXd& patch_rows) {
  double largest_transfer = 0, largest_mismatch = 0, mismatch_sum = 0, transfer_sum = 0;
  for (Eigen::Index i = 0; i < patch_rows.rows(); ++i)
    for (Eigen::Index j = i + 1; j < patch_rows.cols(); ++j) {
      const double a = patches[static_cast<std::size_t>(i)].area * patch_rows(i, j);
      const double b = patches[static_cast<std::size_t>(j)].area * patch_rows(j, i);
      largest_transfer = std::max({largest_transfer, a, b});
      largest_mismatch = std::max(largest_mismatch, std::fabs(a - b));
      mismatch_sum += std::fabs(a - b);
      transfer_sum += a + b;
    }
  Reciprocity result;
  result.measured = true;
  if (transfer_sum > 0) result.mean_error = mismatch_sum / transfer_sum;
  if (largest_transfer > 0) result.max_error = largest_mismatch / largest_transfer;
  return result;
}

}  // namespace candela
