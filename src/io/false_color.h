// False-color pictures of per-pixel scalars (error maps, probe grids) with their scale drawn
// beneath them: `candela compare --diff`, and any command that shows a quantity over an image.
//
// Color maps take t in [0, 1] (clamped; NaN reads as 0) and return sRGB-encoded display values
// in [0, 1], as the maps are published:
//   viridis    perceptually uniform, dark blue-violet (t = 0) → green → yellow (t = 1); the
//              6th-degree polynomial fit of matplotlib's viridis (Stéfan van der Walt and
//              Nathaniel Smith, CC0) published by Matt Zucconi (CC0), within ~0.02 of the table.
//   diverging  blue (t = 0) → white (t = 0.5) → red (t = 1), linear in display values between
//              Moreland's cool-warm end colors (0.230, 0.299, 0.754) and (0.706, 0.016, 0.150):
//              for signed quantities on a scale symmetric about 0.
//
// Layout of false_color_image(values, W, H, ...): a W × (H + color_bar_height(W)) Film.
//   rows 0 .. H−1       the picture: pixel (x, y) shows values[y·W + x]; a non-finite value (NaN:
//                       masked out, no data) is dark grey (display 0.25).
//   the band below     black background; 3 rows gap, then the color bar, 16 rows high, full
//                       width: column x shows t = x / (W − 1) (so column 0 is the map at `low`
//                       and column W − 1 at `high`); below it white tick marks (3 rows) at the
//                       left edge, the centre and the right edge, and under them the labels
//                       low, (low + high)/2 and high in DejaVu Sans (io/text.h), 10 pixels high
//                       below 160 columns, 14 from 160. The low label is left-aligned, the high
//                       one right-aligned, the middle one centred; a label that would overlap
//                       another (narrow images) is left out: the middle first, then the high one.
//                       Labels are drawn whole or not at all: all of them smaller when the low one
//                       is wider than the image, none below 5 pixels. With a quantity, a caption
//                       line beneath: "illuminance (lx)", and the labels are bare numbers.
// The Film holds LINEAR RGB like every Film: written with the default DisplaySettings (sRGB,
// clamp, exposure 0) the PNG's bytes are the map's display colors (to 8-bit rounding).
#pragma once

#include <string>
#include <vector>

#include "camera/film.h"
#include "math/vector.h"

namespace candela {

enum class ColorMap { viridis, diverging };

Color color_map_viridis(double t);
Color color_map_diverging(double t);
Color color_map(ColorMap map, double t);

// The display color of masked-out / missing values.
inline constexpr double kNoDataGrey = 0.25;

// Rows below the picture taken by the color bar and its labels, for an image `width` wide, with
// the caption's line (FalseColorScale::quantity) or without it.
int color_bar_height(int width, bool caption = false);

// A number as the color bar labels it: "0", or 3 significant digits in the shortest of fixed
// and exponent notation ("0.0123", "12.5", "1.23e-05", "-4.5e+06").
std::string format_scale_value(double value);

// How values become colors (Radiance's falsecolor -s, -log and -cl): the range [low, high],
// linear or logarithmic (t = log(v / low) / log(high / low); needs low > 0), and `contours`
// bands: with contours = n > 1 the scale is cut into n equal steps of t and a black line is drawn
// where two neighbouring pixels fall in different steps (iso-lines of the quantity), with a tick
// at each step on the color bar.
struct FalseColorScale {
  double low = 0, high = 1;
  bool logarithmic = false;
  int contours = 0;  // 0 or 1: none
  // The quantity's unit ("lx", "cd/m²"): the bar's labels carry it ("0 lx", "600 lx") unless
  // there is a quantity, whose caption line says both: "illuminance (lx)".
  std::string unit;
  std::string quantity;  // "illuminance", "|Y − Y_ref|"; "" : no caption
  // Where value falls on the scale, t in [0, 1] (values outside take the ends; NaN stays NaN).
  double position(double value) const;
};

// The scale of a false-colour picture (Radiance's falsecolor): `range` {LO, HI} when given (two
// values), else 0 to `maximum` (1 when it is not positive) — logarithmic: three decades below it,
// as falsecolor -log 3 — with `contours` steps and the quantity and unit under the bar.
FalseColorScale false_color_scale(double maximum, const std::vector<double>& range, bool logarithmic,
                                  int contours, const std::string& unit, const std::string& quantity = "");

// values: width·height numbers, row by row, top row first. The scale runs from low (t = 0) to
// high (t = 1); values outside it take the end colors. Throws std::invalid_argument when the
// sizes disagree, width or height is not positive, or !(low < high) (both must be finite; low > 0
// for a logarithmic scale), or contours is negative or above 256.
Film false_color_image(const std::vector<double>& values, int width, int height, const FalseColorScale& scale,
                       ColorMap map);
// The linear scale [low, high] without contours.
Film false_color_image(const std::vector<double>& values, int width, int height, double low, double high,
                       ColorMap map);

}  // namespace candela
