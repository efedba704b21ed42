// The error-against-time chart: log-log axes over whole decades, a polyline per method
// with steps, a marker for a method of one point, text escaped.
#include "validate/convergence_chart.h"

#include <gtest/gtest.h>

#include <string>

namespace candela {
namespace {

int count(const std::string& text, const std::string& what) {
  int n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

TEST(ConvergenceChart, LogLogAxesOverWholeDecadesAndOneMarkerForAMethodWithoutSteps) {
  std::vector<ConvergenceRow> path, whitted;
  for (int pass = 1; pass <= 4; ++pass)
    path.push_back({"path", "passes", uint64_t(pass), 0.02 * pass, 0.001, 0.4 / pass, 0.1, std::nullopt});
  path.push_back({"path", "final", 4, 0.09, 0, 0.1, 0.1, std::nullopt});
  whitted.push_back({"whitted <&>", "final", 1, 0.005, 0, 0.3, 0.2, std::nullopt});
  const std::vector<ChartSeries> series = convergence_series({path, whitted, {}});
  ASSERT_EQ(series.size(), 2u);
  EXPECT_TRUE(series[0].line);
  EXPECT_FALSE(series[1].line);
  EXPECT_NE(series[0].color, series[1].color);
  EXPECT_DOUBLE_EQ(series[0].xy[1].first, 0.041);  // time to the image: seconds + image_seconds
  EXPECT_DOUBLE_EQ(series[0].xy[1].second, 0.2);

  ChartAxes axes;
  axes.title = "room: error against time";
  axes.x_label = "time to the image (s)";
  axes.y_label = "RMSE";
  const std::string svg = log_log_chart_svg(series, axes);
  EXPECT_EQ(count(svg, "<polyline"), 1);
  // x from 0.001 to 0.1 (0.005 … 0.09), y from 0.1 to 1 (0.1 … 0.4): decades, 2× and 5× labelled.
  for (const char* label : {">0.001<", ">0.002<", ">0.005<", ">0.01<", ">0.1<", ">0.2<", ">0.5<", ">1<"})
    EXPECT_NE(svg.find(label), std::string::npos) << label;
  EXPECT_EQ(svg.find(">10<"), std::string::npos);
  EXPECT_NE(svg.find(">whitted &lt;&amp;&gt;<"), std::string::npos);
  EXPECT_EQ(svg.find("whitted <&>"), std::string::npos);
  EXPECT_NE(svg.find(">room: error against time<"), std::string::npos);
  // Markers: path's last point and its legend, whitted's point and its legend.
  EXPECT_EQ(count(svg, "<circle"), 4);

  // Values that a log axis cannot show (0, negative, infinite) are left out, not drawn at −∞.
  const std::string empty =
      log_log_chart_svg({{"zero", "#000000", {{0.0, 1.0}, {1.0, 0.0}}, true, false}}, axes);
  EXPECT_EQ(count(empty, "<polyline"), 0);
  EXPECT_EQ(empty.find("nan"), std::string::npos);
  EXPECT_EQ(empty.find("inf"), std::string::npos);
}

TEST(ConvergenceChart, LongRangesLabelPowersOfTen) {
  const std::string svg =
      log_log_chart_svg({{"wide", "#000000", {{1e-6, 1e-7}, {1e3, 10.0}}, true, false}}, ChartAxes{});
  EXPECT_NE(svg.find("10<tspan dy=\"-6\" font-size=\"10\">-6</tspan>"), std::string::npos);
  EXPECT_NE(svg.find(">0.001<"), std::string::npos);
  EXPECT_NE(svg.find(">1000<"), std::string::npos);
  EXPECT_EQ(svg.find(">0.002<"), std::string::npos);  // no 2× labels over nine decades
}

}  // namespace
}  // namespace candela
