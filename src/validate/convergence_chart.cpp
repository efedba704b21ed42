#include "validate/convergence_chart.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "validate/cross_method_report.h"  // html_escape: SVG text is XML

namespace candela {

namespace {

// A decade's label: 0.001, 0.01 … 1000 as numbers, beyond that 10 with a superscript exponent.
std::string tick_label(double value) {
  const double exponent = std::log10(value);
  const double rounded = std::round(exponent);
  if (std::fabs(exponent - rounded) < 1e-9 && (rounded < -3 || rounded > 4))
    return fmt::format("10<tspan dy=\"-6\" font-size=\"10\">{}</tspan>", static_cast<int>(rounded));
  return fmt::format("{:g}", value);
}

}  // namespace

std::string log_log_chart_svg(const std::vector<ChartSeries>& series, const ChartAxes& axes) {
  double x_low = std::numeric_limits<double>::infinity(), x_high = 0;
  double y_low = x_low, y_high = 0;
  for (const ChartSeries& s : series)
    for (const auto& [x, y] : s.xy) {
      if (!(x > 0) || !(y > 0) || !std::isfinite(x) || !std::isfinite(y)) continue;
      x_low = std::min(x_low, x);
      x_high = std::max(x_high, x);
      y_low = std::min(y_low, y);
      y_high = std::max(y_high, y);
    }
  if (!(x_high > 0)) x_low = 0.1, x_high = 1, y_low = 0.1, y_high = 1;
  const double x0 = std::floor(std::log10(x_low)), x1 = std::max(std::ceil(std::log10(x_high)), x0 + 1);
  const double y0 = std::floor(std::log10(y_low)), y1 = std::max(std::ceil(std::log10(y_high)), y0 + 1);
  // Plot area: margins for the tick labels and titles at the left and bottom, the legend at the right.
  const double left = 78, top = axes.title.empty() ? 20 : 44, legend_width = 230;
  const double right = axes.width - legend_width, bottom = axes.height - 58;
  const auto px = [&](double x) { return left + (std::log10(x) - x0) / (x1 - x0) * (right - left); };
  const auto py = [&](double y) { return bottom - (std::log10(y) - y0) / (y1 - y0) * (bottom - top); };

  std::string svg = fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{0}\" height=\"{1}\" viewBox=\"0 0 {0} {1}\" "
      "font-family=\"DejaVu Sans, Verdana, sans-serif\" font-size=\"13\">\n"
      "<rect width=\"{0}\" height=\"{1}\" fill=\"white\"/>\n",
      axes.width, axes.height);
  if (!axes.title.empty())
    svg += fmt::format("<text x=\"{}\" y=\"24\" text-anchor=\"middle\" font-size=\"15\">{}</text>\n",
                       (left + right) / 2, html_escape(axes.title));
  // Grid and ticks: every decade labelled; 2× and 5× as well over short ranges.
  const bool minor_labels = x1 - x0 < 3;
  for (double e = x0; e <= x1 + 1e-9; ++e)
    for (const double m : {1.0, 2.0, 5.0}) {
      const double value = m * std::pow(10.0, e);
      if (std::log10(value) > x1 + 1e-9) continue;
      const double x = px(value);
      svg += fmt::format("<line x1=\"{0:.1f}\" y1=\"{1}\" x2=\"{0:.1f}\" y2=\"{2}\" stroke=\"{3}\"/>\n", x,
                         top, bottom, m == 1 ? "#d0d0d0" : "#ececec");
      if (m == 1 || minor_labels)
        svg += fmt::format("<text x=\"{:.1f}\" y=\"{}\" text-anchor=\"middle\">{}</text>\n", x, bottom + 18,
                           tick_label(value));
    }
  const bool minor_y_labels = y1 - y0 < 3;
  for (double e = y0; e <= y1 + 1e-9; ++e)
    for (const double m : {1.0, 2.0, 5.0}) {
      const double value = m * std::pow(10.0, e);
      if (std::log10(value) > y1 + 1e-9) continue;
      const double y = py(value);
      svg += fmt::format("<line x1=\"{0}\" y1=\"{1:.1f}\" x2=\"{2}\" y2=\"{1:.1f}\" stroke=\"{3}\"/>\n", left,
                         y, right, m == 1 ? "#d0d0d0" : "#ececec");
      if (m == 1 || minor_y_labels)
        svg += fmt::format("<text x=\"{}\" y=\"{:.1f}\" text-anchor=\"end\">{}</text>\n", left - 6, y + 4,
                           tick_label(value));
    }
  svg +=
      fmt::format("<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"none\" stroke=\"#404040\"/>\n",
                  left, top, right - left, bottom - top);
  svg += fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">{}</text>\n", (left + right) / 2,
                     bottom + 42, html_escape(axes.x_label));
  svg += fmt::format("<text transform=\"translate(18 {}) rotate(-90)\" text-anchor=\"middle\">{}</text>\n",
                     (top + bottom) / 2, html_escape(axes.y_label));

  // The curves, then the legend, one line per series.
  const auto marker = [](double x, double y, const ChartSeries& s) {
    return fmt::format(
        "<circle cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"4.5\" fill=\"{}\" stroke=\"{}\" "
        "stroke-width=\"1.6\"/>\n",
        x, y, s.hollow ? "white" : s.color, s.color);
  };
  for (const ChartSeries& s : series) {
    std::vector<std::pair<double, double>> points;
    for (const auto& [x, y] : s.xy)
      if (x > 0 && y > 0 && std::isfinite(x) && std::isfinite(y)) points.emplace_back(px(x), py(y));
    if (points.empty()) continue;
    if (s.line && points.size() > 1) {
      std::string path;
      for (const auto& [x, y] : points) path += fmt::format("{}{:.1f},{:.1f}", path.empty() ? "" : " ", x, y);
      svg += fmt::format("<polyline points=\"{}\" fill=\"none\" stroke=\"{}\" stroke-width=\"2\"/>\n", path,
                         s.color);
      svg += marker(points.back().first, points.back().second, s);
    } else {
      for (const auto& [x, y] : points) svg += marker(x, y, s);
    }
  }
  double legend_y = top + 10;
  for (const ChartSeries& s : series) {
    const double x = right + 16;
    if (s.line && s.xy.size() > 1)
      svg += fmt::format("<line x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\" stroke=\"{}\" stroke-width=\"2\"/>\n",
                         x, legend_y, x + 22, legend_y, s.color);
    svg += marker(x + 11, legend_y, s);
    svg += fmt::format("<text x=\"{}\" y=\"{}\">{}</text>\n", x + 30, legend_y + 4, html_escape(s.label));
    legend_y += 22;
  }
  svg += "</svg>\n";
  return svg;
}

std::vector<ChartSeries> convergence_series(const std::vector<std::vector<ConvergenceRow>>& logs) {
  // Matplotlib's "tab10" colours, which stay apart for the colour-blind better than most.
  static const char* kPalette[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd",
                                   "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"};
  std::vector<ChartSeries> series;
  for (std::size_t i = 0; i < logs.size(); ++i) {
    if (logs[i].empty()) continue;
    ChartSeries s;
    s.label = logs[i].front().method;
    s.color = kPalette[i % std::size(kPalette)];
    for (const ConvergenceRow& row : logs[i]) s.xy.emplace_back(row.time_to_image(), row.rmse);
    s.line = s.xy.size() > 1;
    series.push_back(std::move(s));
  }
  return series;
}

}  // namespace candela
