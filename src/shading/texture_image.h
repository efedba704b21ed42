// A picture read from a file for texturing and environment maps (SPEC §7: image textures,
// PNG/JPG/EXR, bilinear). Pixels are kept as linear float RGB (3 floats a pixel, not Color's
// doubles: textures can be large).
//
// Coordinates: texel (x, y) has x from the left and y from the BOTTOM row of the file (y = 0 is
// the last row stored in a PNG/JPG/EXR), as in OpenGL and OBJ texture coordinates. In (u, v),
// u runs left→right and v bottom→top over [0, 1]; texel (x, y) has its centre at
// ((x + 0.5)/width, (y + 0.5)/height).
#pragma once

#include <cstddef>
#include <filesystem>
#include <string_view>
#include <vector>

#include "math/vector.h"

namespace candela {

// How the numbers stored in a file relate to linear RGB.
enum class ColorEncoding {
  automatic,  // 8- and 16-bit formats (PNG, JPG, BMP, TGA, ...) are sRGB; float formats (EXR, PFM, HDR) linear
  srgb,       // decode with the sRGB EOTF whatever the format
  linear,     // take the values as they are (integers divided by their maximum)
};

// What a lookup does outside [0, 1].
enum class WrapMode {
  repeat,  // the image tiles the plane (and the u = 0/1 seam blends the last and first columns)
  clamp,   // the edge texels extend outward
  mirror,  // tiles, every other tile reflected (OpenGL's GL_MIRRORED_REPEAT)
};

// The names the scene format uses: "auto", "srgb", "linear"; "repeat", "clamp", "mirror".
std::string_view color_encoding_name(ColorEncoding encoding);
std::string_view wrap_mode_name(WrapMode wrap);

// The sRGB electro-optical transfer function (IEC 61966-2-1): encoded value in [0, 1] → linear.
double srgb_decode(double encoded);

class TextureImage {
 public:
  // Larger images are refused: 2^28 pixels are 3 GiB of float RGB already.
  static constexpr std::size_t kMaxPixels = std::size_t(1) << 28;

  // rgb holds width·height·3 floats, linear, row by row starting with the BOTTOM row (y = 0).
  // Throws std::invalid_argument when the sizes do not agree or are not positive.
  TextureImage(int width, int height, std::vector<float> rgb);

  // Reads PNG (8 or 16 bits), JPG, BMP, TGA, GIF (first frame), PSD, 8-bit PNM (PPM/PGM) and
  // Radiance HDR through stb_image, EXR (any channel type, R/G/B or Y) through OpenEXR, PFM
  // through read_pfm. Grey becomes RGB; alpha is dropped. Throws std::runtime_error naming the file and the
  // reason: missing file, unknown extension, corrupt data, no pixels, over kMaxPixels pixels.
  static TextureImage load(const std::filesystem::path& path, ColorEncoding encoding = ColorEncoding::automatic);

  int width() const { return width_; }
  int height() const { return height_; }
  const std::vector<float>& rgb() const { return rgb_; }

  // x in [0, width), y in [0, height) with y = 0 the bottom row; not range-checked.
  Color texel(int x, int y) const {
    const float* p = &rgb_[(std::size_t(y) * std::size_t(width_) + std::size_t(x)) * 3];
    return {p[0], p[1], p[2]};
  }

  // Bilinear interpolation between the four texel centres nearest to uv. Non-finite
  // coordinates read as 0. Allocates nothing.
  Color bilinear(const Vec2& uv, WrapMode wrap) const { return bilinear(uv, wrap, wrap); }
  Color bilinear(const Vec2& uv, WrapMode wrap_u, WrapMode wrap_v) const;

 private:
  int width_, height_;
  std::vector<float> rgb_;
};

}  // namespace candela
