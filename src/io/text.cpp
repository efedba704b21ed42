#include "io/text.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

// The one translation unit with stb_truetype's implementation; the font's file is read here.
#define STB_TRUETYPE_IMPLEMENTATION
#include <stb_truetype.h>

namespace candela {

namespace {

struct Font {
  std::vector<unsigned char> data;
  stbtt_fontinfo info{};
};

const Font& font() {
  static Font loaded;
  static std::once_flag once;
  std::call_once(once, [] {
    std::ifstream in(CANDELA_FONT_FILE, std::ios::binary);
    loaded.data.assign(std::istreambuf_iterator<char>(in), {});
    if (loaded.data.empty() || !stbtt_InitFont(&loaded.info, loaded.data.data(), 0)) loaded.data.clear();
  });
  if (loaded.data.empty())
    throw std::runtime_error(std::string("cannot read the font ") + CANDELA_FONT_FILE +
                             " (Debian package fonts-dejavu-core; scripts/install-deps.sh installs it)");
  return loaded;
}

// The code points of UTF-8 text; a malformed byte stands for itself (Latin-1).
std::vector<int> code_points(std::string_view utf8) {
  std::vector<int> points;
  for (std::size_t i = 0; i < utf8.size();) {
    const auto byte = static_cast<unsigned char>(utf8[i]);
    const int length = byte < 0x80         ? 1
                       : (byte >> 5) == 6  ? 2
                       : (byte >> 4) == 14 ? 3
                       : (byte >> 3) == 30 ? 4
                                           : 0;
    if (length == 0 || i + length > utf8.size()) {
      points.push_back(byte);
      ++i;
      continue;
    }
    int point = length == 1 ? byte : byte & (0x7f >> length);
    bool valid = true;
    for (int k = 1; k < length; ++k) {
      const auto next = static_cast<unsigned char>(utf8[i + k]);
      valid = valid && (next >> 6) == 2;
      point = point << 6 | (next & 0x3f);
    }
    // Overlong forms, surrogates and points past U+10FFFF are not UTF-8 either.
    constexpr int kLeast[5] = {0, 0, 0x80, 0x800, 0x10000};
    if (!valid || point < kLeast[length] || (point >= 0xd800 && point <= 0xdfff) || point > 0x10ffff) {
      points.push_back(byte);
      ++i;
      continue;
    }
    points.push_back(point);
    i += length;
  }
  return points;
}

}  // namespace

int text_width(std::string_view utf8, double height) {
  const Font& f = font();
  const float scale = stbtt_ScaleForPixelHeight(&f.info, static_cast<float>(height));
  double width = 0;
  const std::vector<int> points = code_points(utf8);
  for (std::size_t i = 0; i < points.size(); ++i) {
    int advance = 0, bearing = 0;
    stbtt_GetCodepointHMetrics(&f.info, points[i], &advance, &bearing);
    width += advance * scale;
    if (i + 1 < points.size())
      width += scale * stbtt_GetCodepointKernAdvance(&f.info, points[i], points[i + 1]);
  }
  return static_cast<int>(std::ceil(width));
}

void draw_text(Film& film, int x, int y, std::string_view utf8, const Color& color, double height,
               TextDirection direction) {
  const Font& f = font();
  const float scale = stbtt_ScaleForPixelHeight(&f.info, static_cast<float>(height));
  int ascent = 0, descent = 0, gap = 0;
  stbtt_GetFontVMetrics(&f.info, &ascent, &descent, &gap);
  const int baseline = static_cast<int>(std::lround(ascent * scale));
  // Along the text (pen) and across it (row below the box's top), then placed by the direction.
  const auto blend = [&](int along, int across, double coverage) {
    const int px = direction == TextDirection::horizontal ? x + along : x + across;
    const int py = direction == TextDirection::horizontal ? y + across : y - along;
    if (px < 0 || py < 0 || px >= film.width() || py >= film.height()) return;
    Color& pixel = film.at(px, py);
    pixel = pixel * (1 - coverage) + color * coverage;
  };
  double pen = 0;
  const std::vector<int> points = code_points(utf8);
  for (std::size_t i = 0; i < points.size(); ++i) {
    int width = 0, rows = 0, x_offset = 0, y_offset = 0;
    unsigned char* bitmap =
        stbtt_GetCodepointBitmap(&f.info, scale, scale, points[i], &width, &rows, &x_offset, &y_offset);
    const int left = static_cast<int>(std::lround(pen)) + x_offset;
    for (int row = 0; row < rows; ++row)
      for (int column = 0; column < width; ++column)
        if (const unsigned char c = bitmap[row * width + column])
          blend(left + column, baseline + y_offset + row, c / 255.0);
    stbtt_FreeBitmap(bitmap, nullptr);
    int advance = 0, bearing = 0;
    stbtt_GetCodepointHMetrics(&f.info, points[i], &advance, &bearing);
    pen += advance * scale;
    if (i + 1 < points.size())
      pen += scale * stbtt_GetCodepointKernAdvance(&f.info, points[i], points[i + 1]);
  }
}

}  // namespace candela
