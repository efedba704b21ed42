// Error against time for several methods on one log-log chart, as SVG — crisp at any
// size, its text set by the viewer's fonts (DejaVu Sans first). candela report puts it on its
// page; docs/validation.md shows the Cornell box's.
#pragma once

#include <string>
#include <vector>

#include "validate/convergence_log.h"

namespace candela {

struct ChartSeries {
  std::string label;
  std::string color;                          // SVG color, "#1f77b4"
  std::vector<std::pair<double, double>> xy;  // points with x, y > 0 (others are left out)
  bool line = true;                           // false: markers alone
  bool hollow = false;                        // hollow markers (the equal-time runs)
};

struct ChartAxes {
  std::string title, x_label, y_label;
  int width = 760, height = 460;
};

// Both axes logarithmic, from the decade below the smallest value to the decade above the largest,
// with a labelled tick at each decade (and 2× and 5× ones when the range is under three decades), a
// legend to the right of the plot. A series of one point is drawn as a marker.
std::string log_log_chart_svg(const std::vector<ChartSeries>& series, const ChartAxes& axes);

// One series per method: each log's rows (time to image, RMSE), the colours of a fixed palette in
// the order given; a log of one row (a method without steps) is one marker.
std::vector<ChartSeries> convergence_series(const std::vector<std::vector<ConvergenceRow>>& logs);

}  // namespace candela
