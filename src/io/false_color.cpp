#include "io/false_color.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "io/text.h"
#include "math/srgb.h"

namespace candela {

namespace {

double clamp_unit(double t) {
  return std::isnan(t) ? 0.0 : std::clamp(t, 0.0, 1.0);
}

Color lerp(const Color& a, const Color& b, double t) {
  return a + (b - a) * t;
}

Color clamp_color(const Color& c) {
  return {std::clamp(c.r, 0.0, 1.0), std::clamp(c.g, 0.0, 1.0), std::clamp(c.b, 0.0, 1.0)};
}

Color display_to_linear(const Color& c) {
  return {srgb_decode(c.r), srgb_decode(c.g), srgb_decode(c.b)};
}

// Bar geometry (see the header).
constexpr int kBarGap = 3;
constexpr int kBarRows = 16;
constexpr int kTickRows = 3;
constexpr int kLabelGap = 2;
constexpr int kBottomMargin = 3;

// The labels' DejaVu Sans height in pixels: 14 from 160 columns, 10 below (a smaller picture).
double label_height(int width) {
  return width >= 160 ? 14 : 10;
}
constexpr double kSmallestText = 5;  // a label shrunk below this is left out

}  // namespace

Color color_map_viridis(double t) {
  t = clamp_unit(t);
  // Coefficients of t^0 .. t^6 per channel (Matt Zucconi's fit, CC0).
  static constexpr double kCoefficients[7][3] = {
      {0.2777273272234177, 0.005407344544966578, 0.3340998053353061},
      {0.1050930431085774, 1.404613529898575, 1.384590162594685},
      {-0.3308618287255563, 0.214847559468213, 0.09509516302823659},
      {-4.634230498983486, -5.799100973351585, -19.33244095627987},
      {6.228269936347081, 14.17993336680509, 56.69055260068105},
      {4.776384997670288, -13.74514537774601, -65.35303263337234},
      {-5.435455855934631, 4.645852612178535, 26.3124352495832},
  };
  Color c;
  for (int channel = 0; channel < 3; ++channel) {
    double value = 0;
    for (int power = 6; power >= 0; --power) value = value * t + kCoefficients[power][channel];
    c[channel] = value;
  }
  return clamp_color(c);
}

Color color_map_diverging(double t) {
  t = clamp_unit(t);
  const Color blue(0.230, 0.299, 0.754), white(1.0), red(0.706, 0.016, 0.150);
  return t <= 0.5 ? lerp(blue, white, t / 0.5) : lerp(white, red, (t - 0.5) / 0.5);
}

Color color_map(ColorMap map, double t) {
  switch (map) {
    case ColorMap::viridis:
      return color_map_viridis(t);
    case ColorMap::diverging:
      return color_map_diverging(t);
  }
  return color_map_viridis(t);
}

int color_bar_height(int width, bool caption) {
  const int text = static_cast<int>(std::ceil(label_height(width)));
  return kBarGap + kBarRows + kTickRows + kLabelGap + text + kBottomMargin + (caption ? text + kLabelGap : 0);
}

std::string format_scale_value(double value) {
  if (value == 0) return "0";
  const std::string general = fmt::format("{:.3g}", value);
  const std::string exponent = fmt::format("{:.2e}", value);
  // {:.3g} switches to exponent notation itself outside 1e-5 .. 1e3; keep the shorter.
  return general.size() <= exponent.size() ? general : exponent;
}

double FalseColorScale::position(double value) const {
  if (std::isnan(value)) return value;
  if (logarithmic) return value <= low ? 0.0 : clamp_unit(std::log(value / low) / std::log(high / low));
  return clamp_unit((value - low) / (high - low));
}

FalseColorScale false_color_scale(double maximum, const std::vector<double>& range, bool logarithmic,
                                  int contours, const std::string& unit, const std::string& quantity) {
  FalseColorScale scale;
  scale.high = maximum > 0 ? maximum : 1;
  scale.low = logarithmic ? scale.high / 1000 : 0;
  if (range.size() == 2) {
    scale.low = range[0];
    scale.high = range[1];
  }
  scale.logarithmic = logarithmic;
  scale.contours = contours;
  scale.unit = unit;
  scale.quantity = quantity;
  return scale;
}

Film false_color_image(const std::vector<double>& values, int width, int height, double low, double high,
                       ColorMap map) {
  FalseColorScale scale;
  scale.low = low;
  scale.high = high;
  return false_color_image(values, width, height, scale, map);
}

Film false_color_image(const std::vector<double>& values, int width, int height, const FalseColorScale& range,
                       ColorMap map) {
  if (width <= 0 || height <= 0)
    throw std::invalid_argument(
        fmt::format("false-color image size must be positive, got {}x{}", width, height));
  if (values.size() != std::size_t(width) * std::size_t(height))
    throw std::invalid_argument(
        fmt::format("false-color image of {}x{} pixels given {} values", width, height, values.size()));
  const double low = range.low, high = range.high;
  if (!std::isfinite(low) || !std::isfinite(high) || !(low < high))
    throw std::invalid_argument(
        fmt::format("false-color scale {} .. {} must be finite with low < high", low, high));
  if (range.logarithmic && !(low > 0))
    throw std::invalid_argument(fmt::format("a logarithmic false-color scale needs low > 0, got {}", low));
  if (range.contours < 0 || range.contours > 256)
    throw std::invalid_argument(fmt::format("false-color contours must be 0 to 256, got {}", range.contours));
  const bool caption = !range.quantity.empty();
  const int band = color_bar_height(width, caption);
  Film film(width, height + band);
  const Color no_data = display_to_linear(Color(kNoDataGrey));
  const int steps = range.contours > 1 ? range.contours : 0;
  // The step of t a pixel is in (-1: no data), for the iso-lines.
  const auto step_of = [&](int x, int y) {
    const double t = range.position(values[std::size_t(y) * std::size_t(width) + std::size_t(x)]);
    return std::isnan(t) ? -1 : std::min(steps - 1, static_cast<int>(t * steps));
  };
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const double t = range.position(values[std::size_t(y) * std::size_t(width) + std::size_t(x)]);
      film.at(x, y) = std::isnan(t) ? no_data : display_to_linear(color_map(map, t));
      if (steps > 0 && !std::isnan(t)) {
        const int here = step_of(x, y);
        const bool edge = (x + 1 < width && step_of(x + 1, y) >= 0 && step_of(x + 1, y) != here) ||
                          (y + 1 < height && step_of(x, y + 1) >= 0 && step_of(x, y + 1) != here);
        if (edge) film.at(x, y) = Color(0.0);
      }
    }
  // The band: black, then the bar.
  const int bar_top = height + kBarGap;
  for (int x = 0; x < width; ++x) {
    const double t = width == 1 ? 0.5 : double(x) / (width - 1);
    const Color color = display_to_linear(color_map(map, t));
    for (int y = bar_top; y < bar_top + kBarRows; ++y) film.at(x, y) = color;
  }
  // Ticks and labels: low (left), high (right), middle (centre) while they do not overlap, in
  // DejaVu Sans; all of them smaller when the low one alone is wider than the image, none when that
  // would make them unreadable — a label is drawn whole or not at all.
  const Color white(1.0);
  const int tick_width = width >= 160 ? 2 : 1;
  const int tick_top = bar_top + kBarRows, label_top = tick_top + kTickRows + kLabelGap;
  // With a caption ("illuminance (lx)") the numbers go bare; without one each carries the unit.
  const std::string suffix = caption || range.unit.empty() ? "" : " " + range.unit;
  const std::string low_label = format_scale_value(low) + suffix,
                    high_label = format_scale_value(high) + suffix;
  const std::string middle_label =
      format_scale_value(range.logarithmic ? std::sqrt(low * high) : low + (high - low) / 2) + suffix;
  const double full_height = label_height(width);
  const auto fitted = [&](const std::string& text) {  // the height at which text fits the width
    const int text_wide = text_width(text, full_height);
    return text_wide <= width ? full_height : full_height * width / text_wide;
  };
  const double height_of_labels = fitted(low_label);
  const auto draw_label = [&](int x, const std::string& label) {
    // draw_text's box top is the ascender line: a fifth of the height above the digits' tops.
    draw_text(film, x, label_top - static_cast<int>(0.2 * height_of_labels), label, white, height_of_labels);
  };
  const auto tick = [&](int x) {
    for (int y = tick_top; y < tick_top + kTickRows; ++y)
      for (int dx = 0; dx < tick_width; ++dx)
        if (x + dx >= 0 && x + dx < width) film.at(x + dx, y) = white;
  };
  tick(0);
  for (int k = 1; k < steps; ++k) tick(static_cast<int>(std::lround(double(k) / steps * (width - 1))));
  if (height_of_labels >= kSmallestText) {
    const int low_width = text_width(low_label, height_of_labels),
              high_width = text_width(high_label, height_of_labels),
              middle_width = text_width(middle_label, height_of_labels);
    const int space = text_width("  ", height_of_labels);  // between two labels
    draw_label(0, low_label);
    const bool high_fits = low_width + space + high_width <= width;
    if (high_fits) {
      tick(width - tick_width);
      draw_label(width - high_width, high_label);
    }
    const int middle_x = (width - middle_width) / 2;
    if (high_fits && middle_x >= low_width + space && middle_x + middle_width + space <= width - high_width) {
      tick(width / 2 - tick_width / 2);
      draw_label(middle_x, middle_label);
    }
  }
  // The caption: what the colours measure, and in what unit.
  if (caption) {
    const std::string text = range.unit.empty() ? range.quantity : range.quantity + " (" + range.unit + ")";
    const double height = fitted(text);
    if (height >= kSmallestText)
      draw_text(
          film, (width - text_width(text, height)) / 2,
          label_top + static_cast<int>(std::ceil(full_height)) + kLabelGap - static_cast<int>(0.2 * height),
          text, white, height);
  }
  return film;
}

}  // namespace candela
