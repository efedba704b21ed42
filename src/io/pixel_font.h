// A 3×5 pixel font for numbers drawn into images: plot tick labels (validate/line_plot.h) and
// color-bar labels (io/false_color.h). Glyphs: the digits, '.', '-', '+' and 'e' — enough for
// numbers such as "0.0123", "-4" or "1.2e-05". Any other character is a blank of the same width.
#pragma once

#include <array>
#include <cstdint>
#include <string_view>

#include "camera/film.h"
#include "math/vector.h"

namespace candela {

inline constexpr int kPixelFontWidth = 3;    // glyph pixels
inline constexpr int kPixelFontHeight = 5;   // glyph pixels
inline constexpr int kPixelFontAdvance = 4;  // glyph pixels from one character to the next

// One glyph: five rows, top first; in each row bit 2 is the left column, bit 0 the right one.
using PixelGlyph = std::array<uint8_t, kPixelFontHeight>;

// The glyph of c, or null when the font has none.
const PixelGlyph* pixel_font_glyph(char c);

// Width in film pixels of text drawn with each glyph pixel a scale × scale block (the last
// character's advance gap not counted).
int pixel_text_width(std::string_view text, int scale);

// Draws text with its top-left corner at (x, y), each glyph pixel a scale × scale block of
// color; parts outside the film are clipped.
void draw_pixel_text(Film& film, int x, int y, std::string_view text, const Color& color, int scale);

}  // namespace candela
