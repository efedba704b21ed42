// A small line-plot rasterizer for the validation cases (SPEC §13): one or more panels side by side,
// each with axes, tick marks labelled with numbers, one colored polyline per curve and a legend of
// colored boxes; every text — the numbers, a panel's title (wrapped over several lines when wider
// than the panel), axis labels and the curves' names — in DejaVu Sans (io/text.h). It draws into a
// Film (linear RGB in [0, 1]) that io/image_writer.h writes as PNG.
#pragma once

#include <string>
#include <vector>

#include "camera/film.h"
#include "math/vector.h"

namespace candela {

struct PlotCurve {
  std::vector<double> x, y;  // the same length; drawn as a polyline in the order given
  Color color;
  int width = 1;  // line width in pixels
  bool dashed = false;
  bool markers = false;  // a small square at each point
  std::string label;     // the legend's name for it ("" : a box alone)
};

struct PlotPanel {
  std::vector<PlotCurve> curves;
  double x_min = 0, x_max = 1;          // the x range shown
  double y_min = 0, y_max = 0;          // the y range shown; y_max <= y_min: from the curves (with 0)
  double x_tick = 0, y_tick = 0;        // tick spacing; 0: about five ticks
  std::string title, x_label, y_label;  // "" : none (and no room kept for it)
};

// Panels side by side, each panel_width × panel_height pixels; the legend (one box per curve of
// the first panel, in order) sits in the first panel's top right corner.
Film draw_line_plot(const std::vector<PlotPanel>& panels, int panel_width = 480, int panel_height = 360);

// draw_line_plot written as a PNG of the colors as given (no sRGB curve).
void write_line_plot_png(const std::string& path, const std::vector<PlotPanel>& panels, int panel_width = 480,
                         int panel_height = 360);

}  // namespace candela
