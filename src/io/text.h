// Text drawn into images with a TrueType font — DejaVu Sans (Debian's fonts-dejavu-core, found at
// configure time) rasterized by stb_truetype (libstb-dev, as stb_image): every number, title,
// axis label and legend of the validation plots (validate/line_plot.h) and of the false-colour
// scales (io/false_color.h).
#pragma once

#include <string_view>

#include "camera/film.h"
#include "math/vector.h"

namespace candela {

enum class TextDirection {
  horizontal,  // left to right
  upward,      // turned 90° counter-clockwise: bottom to top (a y axis's label)
};

// The advance width in pixels of UTF-8 text at a font size of `height` pixels (ascent to descent).
int text_width(std::string_view utf8, double height);

// Draws UTF-8 text of `height` pixels blended over the film by the glyphs' coverage: horizontal
// text with its box's top-left corner at (x, y); upward text with its box's bottom-left corner
// there (the text reads upward from y). Parts outside the film are clipped. Throws
// std::runtime_error when the font file cannot be read (the install is incomplete).
void draw_text(Film& film, int x, int y, std::string_view utf8, const Color& color, double height,
               TextDirection direction = TextDirection::horizontal);

}  // namespace candela
