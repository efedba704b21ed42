#include "io/pixel_font.h"

#include <algorithm>

namespace candela {

namespace {

constexpr std::array<PixelGlyph, 14> kGlyphs{{
    {7, 5, 5, 5, 7},  // 0
    {2, 6, 2, 2, 7},  // 1
    {7, 1, 7, 4, 7},  // 2
    {7, 1, 7, 1, 7},  // 3
    {5, 5, 7, 1, 1},  // 4
    {7, 4, 7, 1, 7},  // 5
    {7, 4, 7, 5, 7},  // 6
    {7, 1, 1, 1, 1},  // 7
    {7, 5, 7, 5, 7},  // 8
    {7, 5, 7, 1, 7},  // 9
    {0, 0, 0, 0, 2},  // .
    {0, 0, 7, 0, 0},  // -
    {0, 2, 7, 2, 0},  // +
    {0, 7, 7, 4, 7},  // e (lower case: the bowl on rows 2–3, the open side bottom right)
}};

}  // namespace

const PixelGlyph* pixel_font_glyph(char c) {
  if (c >= '0' && c <= '9') return &kGlyphs[static_cast<std::size_t>(c - '0')];
  switch (c) {
    case '.':
      return &kGlyphs[10];
    case '-':
      return &kGlyphs[11];
    case '+':
      return &kGlyphs[12];
    case 'e':
      return &kGlyphs[13];
    default:
      return nullptr;
  }
}

int pixel_text_width(std::string_view text, int scale) {
  if (text.empty()) return 0;
  return (static_cast<int>(text.size()) * kPixelFontAdvance - (kPixelFontAdvance - kPixelFontWidth)) * scale;
}

void draw_pixel_text(Film& film, int x, int y, std::string_view text, const Color& color, int scale) {
  for (const char c : text) {
    if (const PixelGlyph* glyph = pixel_font_glyph(c))
      for (int row = 0; row < kPixelFontHeight; ++row)
        for (int column = 0; column < kPixelFontWidth; ++column) {
          if (!((*glyph)[row] & (4 >> column))) continue;
          const int x0 = std::max(0, x + column * scale),
                    x1 = std::min(film.width(), x + (column + 1) * scale);
          const int y0 = std::max(0, y + row * scale), y1 = std::min(film.height(), y + (row + 1) * scale);
          for (int py = y0; py < y1; ++py)
            for (int px = x0; px < x1; ++px) film.at(px, py) = color;
        }
    x += kPixelFontAdvance * scale;
  }
}

}  // namespace candela
