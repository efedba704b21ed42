#include "util/statistics.h"

#include <gtest/gtest.h>

namespace candela {
namespace {

// A method that traced no ray in the phase (a rasterized display) is not summarised as
// "0 rays, 0.00 Mrays/s"; one that did gets its rate.
TEST(RunStatistics, SummarySaysNoRaysRatherThanZeroMraysPerSecond) {
  RunStatistics rasterized;
  rasterized.add_phase("render", 2.0);
  const std::string none = rasterized.summary();
  EXPECT_NE(none.find("rays: none traced"), std::string::npos) << none;
  EXPECT_EQ(none.find("Mrays/s"), std::string::npos) << none;

  RunStatistics traced;
  traced.add_phase("render", 2.0);
  traced.rays.primary = 3'000'000;
  traced.rays.shadow = 1'000'000;
  const std::string rate = traced.summary();
  EXPECT_NE(rate.find("(4000000 total, 2.00 Mrays/s)"), std::string::npos) << rate;
  // A slow render keeps its digits (8 bunnies by the list read "0.00 Mrays/s").
  RunStatistics slow;
  slow.add_phase("render", 10.8);
  slow.rays.primary = 20'000;
  const std::string slow_rate = slow.summary();
  EXPECT_NE(slow_rate.find("0.00185 Mrays/s"), std::string::npos) << slow_rate;
}

}  // namespace
}  // namespace candela
