// Reading pictures: PNG/JPG/BMP/TGA/GIF/PSD/PNM/HDR through stb_image, EXR through OpenEXR, PFM
// by hand, into linear float RGB (SPEC §7: image textures and environment maps; `candela
// compare`). The readers refuse, naming the file, what fuzzing found to crash or exhaust memory
// (see the size checks in image_reader.cpp). Texture lookup and filtering are shading's
// (shading/texture_image.h).
//
// Coordinates: pixel (x, y) has x from the left and y from the BOTTOM row of the file (y = 0 is
// the last row stored in a PNG/JPG/EXR), as in OpenGL and OBJ texture coordinates.
#pragma once

#include <cstddef>
#include <filesystem>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "camera/film.h"
#include "math/vector.h"
#include "util/enum_names.h"

namespace candela {

// How the numbers stored in a file relate to linear RGB.
enum class ColorEncoding {
  automatic,  // 8- and 16-bit formats (PNG, JPG, BMP, TGA, ...) are sRGB; float formats (EXR, PFM, HDR)
              // linear
  srgb,       // decode with the sRGB EOTF whatever the format
  linear,     // take the values as they are (integers divided by their maximum)
};

// The names the scene format uses: "auto", "srgb", "linear".
inline constexpr auto kColorEncodingNames = enum_names<ColorEncoding>(
    {{ColorEncoding::automatic, "auto"}, {ColorEncoding::srgb, "srgb"}, {ColorEncoding::linear, "linear"}});

// Linear float RGB pixels (3 floats a pixel, not Color's doubles: pictures can be large), row by
// row starting with the BOTTOM row (y = 0).
class RgbImage {
 public:
  // Larger images are refused: 2^28 pixels are 3 GiB of float RGB already.
  static constexpr std::size_t kMaxPixels = std::size_t(1) << 28;

  // rgb holds width·height·3 floats. Throws std::invalid_argument when the sizes do not agree,
  // are not positive or exceed kMaxPixels.
  RgbImage(int width, int height, std::vector<float> rgb);

  int width() const { return width_; }
  int height() const { return height_; }
  const std::vector<float>& rgb() const { return rgb_; }

  // x in [0, width), y in [0, height) with y = 0 the bottom row; not range-checked.
  Color texel(int x, int y) const {
    const float* p = &rgb_[(std::size_t(y) * std::size_t(width_) + std::size_t(x)) * 3];
    return {p[0], p[1], p[2]};
  }

 private:
  int width_, height_;
  std::vector<float> rgb_;
};

// Reads PNG (8 or 16 bits), JPG, BMP, TGA, GIF (first frame), PSD, 8-bit PNM (PPM/PGM) and
// Radiance HDR through stb_image, EXR (any channel type, R/G/B or Y) through OpenEXR, PFM
// through read_pfm. Grey becomes RGB; alpha is dropped. Throws std::runtime_error naming the
// file and the reason: missing file, unknown extension, corrupt data, no pixels, over
// kMaxPixels pixels, a non-finite value or one of magnitude above max_magnitude (the first
// such texel named by x, y and channel).
RgbImage read_image(const std::filesystem::path& path, ColorEncoding encoding = ColorEncoding::automatic,
                    double max_magnitude = std::numeric_limits<double>::infinity());

// Reads a PFM (color "PF" or grey "Pf", either byte order). Throws std::runtime_error.
Film read_pfm(const std::string& path);

}  // namespace candela
