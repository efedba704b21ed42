#include "validate/line_plot.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "camera/tone_map.h"
#include "io/image_writer.h"
#include "io/text.h"

namespace candela {

namespace {

constexpr double kTextHeight = 15;  // pixels of a title, an axis label or a curve's name
constexpr double kTickHeight = 12;  // pixels of a tick's number
constexpr int kLineSpacing = 19;    // between the lines of a title

// Text cut into lines no wider than `width` at its spaces (a word wider than that alone on its
// line): a title longer than its panel is wrapped, never cut.
std::vector<std::string> wrapped(const std::string& text, int width, double height) {
  std::vector<std::string> lines;
  std::string line;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t space = text.find(' ', start);
    const std::string word =
        text.substr(start, space == std::string::npos ? std::string::npos : space - start);
    const std::string longer = line.empty() ? word : line + " " + word;
    if (!line.empty() && text_width(longer, height) > width) {
      lines.push_back(line);
      line = word;
    } else {
      line = longer;
    }
    if (space == std::string::npos) break;
    start = space + 1;
  }
  if (!line.empty()) lines.push_back(line);
  return lines;
}

class Canvas {
 public:
  explicit Canvas(Film& film) : film_(film) {}
  void set(int x, int y, const Color& c) {
    if (x >= clip_x0 && x < clip_x1 && y >= clip_y0 && y < clip_y1) film_.at(x, y) = c;
  }
  void fill(int x0, int y0, int x1, int y1, const Color& c) {
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) set(x, y, c);
  }
  // A line of the given width; dashed: 6 pixels on, 4 off along its length (continued over joins).
  void line(double x0, double y0, double x1, double y1, const Color& c, int width, bool dashed, double& run) {
    const double dx = x1 - x0, dy = y1 - y0;
    const double length = std::hypot(dx, dy);
    const int steps = std::max(1, static_cast<int>(std::ceil(length * 2)));
    for (int i = 0; i <= steps; ++i) {
      const double t = static_cast<double>(i) / steps;
      const double along = run + t * length;
      if (dashed && std::fmod(along, 10.0) >= 6.0) continue;
      const int x = static_cast<int>(std::lround(x0 + t * dx)),
                y = static_cast<int>(std::lround(y0 + t * dy));
      const int lo = -(width - 1) / 2, hi = width / 2;
      for (int oy = lo; oy <= hi; ++oy)
        for (int ox = lo; ox <= hi; ++ox) set(x + ox, y + oy, c);
    }
    run += length;
  }
  int clip_x0 = 0, clip_y0 = 0, clip_x1 = 0, clip_y1 = 0;

 private:
  Film& film_;
};

double nice_step(double range) {
  if (!(range > 0)) return 1;
  const double raw = range / 5;
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  for (const double m : {1.0, 2.0, 5.0, 10.0})
    if (m * power >= raw * 0.999) return m * power;
  return 10 * power;
}

std::string tick_label(double value, double step) {
  const int decimals = std::max(0, static_cast<int>(-std::floor(std::log10(step) + 1e-9)));
  if (std::abs(value) < step * 1e-6) value = 0;
  return fmt::format("{:.{}f}", value, decimals);
}

}  // namespace

Film draw_line_plot(const std::vector<PlotPanel>& panels, int panel_width, int panel_height) {
  const int count = std::max<int>(1, static_cast<int>(panels.size()));
  Film film(panel_width * count, panel_height);
  Canvas canvas(film);
  const Color white(1), black(0), grid(0.88);
  canvas.clip_x1 = film.width();
  canvas.clip_y1 = film.height();
  canvas.fill(0, 0, film.width(), film.height(), white);
  constexpr int right = 12;
  for (int p = 0; p < static_cast<int>(panels.size()); ++p) {
    const PlotPanel& panel = panels[p];
    // Room for the labels only where there are some (the unlabelled plots keep their layout); a
    // title wider than the panel takes as many lines as it needs.
    const std::vector<std::string> title_lines = panel.title.empty()
                                                     ? std::vector<std::string>()
                                                     : wrapped(panel.title, panel_width - 12, kTextHeight);
    const int left = 64 + (panel.y_label.empty() ? 0 : 20),
              top = 12 + kLineSpacing * static_cast<int>(title_lines.size()),
              bottom = 28 + (panel.x_label.empty() ? 0 : 20);
    double y_min = panel.y_min, y_max = panel.y_max;
    if (!(y_max > y_min)) {
      y_min = 0;
      y_max = 0;
      for (const PlotCurve& c : panel.curves)
        for (const double v : c.y)
          if (std::isfinite(v)) y_min = std::min(y_min, v), y_max = std::max(y_max, v);
      if (!(y_max > y_min)) y_max = y_min + 1;
      const double step = nice_step(y_max - y_min);
      y_max = std::ceil(y_max / step - 1e-9) * step;
      y_min = std::floor(y_min / step + 1e-9) * step;
    }
    const double x_min = panel.x_min, x_max = panel.x_max > panel.x_min ? panel.x_max : panel.x_min + 1;
    const int x0 = p * panel_width + left, x1 = (p + 1) * panel_width - right, y0 = top,
              y1 = panel_height - bottom;
    auto px = [&](double x) { return x0 + (x - x_min) / (x_max - x_min) * (x1 - x0); };
    auto py = [&](double y) { return y1 - (y - y_min) / (y_max - y_min) * (y1 - y0); };
    canvas.clip_x0 = 0;
    canvas.clip_x1 = film.width();
    canvas.clip_y0 = 0;
    canvas.clip_y1 = film.height();
    double run = 0;
    // Grid lines and tick labels.
    const double x_step = panel.x_tick > 0 ? panel.x_tick : nice_step(x_max - x_min);
    for (double x = std::ceil(x_min / x_step - 1e-9) * x_step; x <= x_max + 1e-9 * x_step; x += x_step) {
      const int ix = static_cast<int>(std::lround(px(x)));
      canvas.fill(ix, y0, ix + 1, y1, grid);
      canvas.fill(ix, y1, ix + 1, y1 + 5, black);
      const std::string label = tick_label(x, x_step);
      draw_text(film, ix - text_width(label, kTickHeight) / 2, y1 + 7, label, black, kTickHeight);
    }
    const double y_step = panel.y_tick > 0 ? panel.y_tick : nice_step(y_max - y_min);
    for (double y = std::ceil(y_min / y_step - 1e-9) * y_step; y <= y_max + 1e-9 * y_step; y += y_step) {
      const int iy = static_cast<int>(std::lround(py(y)));
      canvas.fill(x0, iy, x1, iy + 1, grid);
      canvas.fill(x0 - 5, iy, x0, iy + 1, black);
      const std::string label = tick_label(y, y_step);
      draw_text(film, x0 - 8 - text_width(label, kTickHeight), iy - 7, label, black, kTickHeight);
    }
    canvas.fill(x0, y0, x0 + 1, y1 + 1, black);  // axes
    canvas.fill(x0, y1, x1, y1 + 1, black);
    // Curves, clipped to the plot area.
    canvas.clip_x0 = x0 + 1;
    canvas.clip_x1 = x1;
    canvas.clip_y0 = y0;
    canvas.clip_y1 = y1;
    for (const PlotCurve& c : panel.curves) {
      run = 0;
      const std::size_t n = std::min(c.x.size(), c.y.size());
      for (std::size_t i = 0; i + 1 < n; ++i)
        if (std::isfinite(c.y[i]) && std::isfinite(c.y[i + 1]))
          canvas.line(px(c.x[i]), py(c.y[i]), px(c.x[i + 1]), py(c.y[i + 1]), c.color, c.width, c.dashed,
                      run);
      if (c.markers)
        for (std::size_t i = 0; i < n; ++i)
          if (std::isfinite(c.y[i])) {
            const int mx = static_cast<int>(std::lround(px(c.x[i]))),
                      my = static_cast<int>(std::lround(py(c.y[i])));
            canvas.fill(mx - 2, my - 2, mx + 3, my + 3, c.color);
          }
    }
    canvas.clip_x0 = 0;
    canvas.clip_x1 = film.width();
    canvas.clip_y0 = 0;
    canvas.clip_y1 = film.height();
    for (std::size_t line = 0; line < title_lines.size(); ++line) {
      const int centre =
          std::clamp((x0 + x1) / 2, p * panel_width + 6 + text_width(title_lines[line], kTextHeight) / 2,
                     (p + 1) * panel_width - 6 - text_width(title_lines[line], kTextHeight) / 2);
      draw_text(film, centre - text_width(title_lines[line], kTextHeight) / 2,
                6 + kLineSpacing * static_cast<int>(line), title_lines[line], black, kTextHeight);
    }
    if (!panel.x_label.empty())
      draw_text(film, (x0 + x1 - text_width(panel.x_label, kTextHeight)) / 2, y1 + 26, panel.x_label, black,
                kTextHeight);
    if (!panel.y_label.empty()) {
      // Along the axis; smaller when longer than the axis, never cut.
      const double height = std::min(
          kTextHeight, kTextHeight * (y1 - y0 + 40) / std::max(1, text_width(panel.y_label, kTextHeight)));
      draw_text(film, p * panel_width + 4,
                std::min(panel_height - 2, (y0 + y1 + text_width(panel.y_label, height)) / 2), panel.y_label,
                black, height, TextDirection::upward);
    }
    // Legend: a box per curve, top right.
    if (p == 0) {
      canvas.clip_x0 = 0;
      canvas.clip_x1 = film.width();
      canvas.clip_y0 = 0;
      canvas.clip_y1 = film.height();
      // Named curves: the names left of their boxes on a white ground.
      int names = 0;
      for (const PlotCurve& c : panel.curves)
        names = std::max(names, c.label.empty() ? 0 : text_width(c.label, kTextHeight));
      if (names > 0)
        canvas.fill(x1 - 34 - names, y0 + 2, x1 - 2, y0 + 4 + 18 * static_cast<int>(panel.curves.size()),
                    white);
      int by = y0 + 6;
      for (const PlotCurve& c : panel.curves) {
        canvas.fill(x1 - 26, by - 1, x1 - 6, by + 11, black);
        canvas.fill(x1 - 25, by, x1 - 7, by + 10, c.color);
        if (!c.label.empty())
          draw_text(film, x1 - 30 - text_width(c.label, kTextHeight), by - 3, c.label, black, kTextHeight);
        by += names > 0 ? 18 : 16;
      }
    }
  }
  return film;
}

void write_line_plot_png(const std::string& path, const std::vector<PlotPanel>& panels, int panel_width,
                         int panel_height) {
  DisplaySettings display;
  display.srgb = false;  // the colors as given
  write_png(draw_line_plot(panels, panel_width, panel_height), path, display);
}

}  // namespace candela
