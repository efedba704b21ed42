// A picture for texturing and environment maps (SPEC §7: image textures, PNG/JPG/EXR,
// bilinear): the pixels io/image_reader.h decodes, with the lookups and wrap modes of texturing.
//
// Coordinates: texel (x, y) has x from the left and y from the BOTTOM row of the file (y = 0 is
// the last row stored in a PNG/JPG/EXR), as in OpenGL and OBJ texture coordinates. In (u, v),
// u runs left→right and v bottom→top over [0, 1]; texel (x, y) has its centre at
// ((x + 0.5)/width, (y + 0.5)/height).
#pragma once

#include <cstddef>
#include <filesystem>
#include <string_view>
#include <utility>
#include <vector>

#include "io/image_reader.h"
#include "math/vector.h"
#include "util/enum_names.h"

namespace candela {

// What a lookup does outside [0, 1].
enum class WrapMode {
  repeat,  // the image tiles the plane (and the u = 0/1 seam blends the last and first columns)
  clamp,   // the edge texels extend outward
  mirror,  // tiles, every other tile reflected (OpenGL's GL_MIRRORED_REPEAT)
};

// The names the scene format uses: "repeat", "clamp", "mirror".
inline constexpr auto kWrapModeNames = enum_names<WrapMode>(
    {{WrapMode::repeat, "repeat"}, {WrapMode::clamp, "clamp"}, {WrapMode::mirror, "mirror"}});

class TextureImage {
 public:
  // Larger images are refused: 2^28 pixels are 3 GiB of float RGB already.
  static constexpr std::size_t kMaxPixels = RgbImage::kMaxPixels;

  // rgb holds width·height·3 floats, linear, row by row starting with the BOTTOM row (y = 0).
  // Throws std::invalid_argument when the sizes do not agree or are not positive.
  TextureImage(int width, int height, std::vector<float> rgb) : pixels_(width, height, std::move(rgb)) {}
  explicit TextureImage(RgbImage pixels) : pixels_(std::move(pixels)) {}

  // The largest magnitude a texel read from a file may have. A texel is multiplied by the
  // texture's or environment's multiplier and by a light's intensity, each at most 1e16 (the
  // scene file's limit on every number, io/json_node.cpp): 1e6 · 1e16 · 1e16 = 1e38 stays below
  // the largest float, 3.4e38, which EXR and PFM pixels are written as. (PFM texels of 3e38 made
  // infinite pixels.) HDR skies reach about 1e5; brighter ones can be scaled down in the file
  // and up by the multiplier.
  static constexpr double kMaxValue = 1e6;

  // The file read by read_image (io/image_reader.h: the formats, and the errors it throws), with
  // texels of magnitude above kMaxValue refused.
  static TextureImage load(const std::filesystem::path& path,
                           ColorEncoding encoding = ColorEncoding::automatic) {
    return TextureImage(read_image(path, encoding, kMaxValue));
  }

  int width() const { return pixels_.width(); }
  int height() const { return pixels_.height(); }
  const std::vector<float>& rgb() const { return pixels_.rgb(); }

  // x in [0, width), y in [0, height) with y = 0 the bottom row; not range-checked.
  Color texel(int x, int y) const { return pixels_.texel(x, y); }

  // Bilinear interpolation between the four texel centres nearest to uv. Non-finite
  // coordinates read as 0. Allocates nothing.
  Color bilinear(const Vec2& uv, WrapMode wrap) const { return bilinear(uv, wrap, wrap); }
  Color bilinear(const Vec2& uv, WrapMode wrap_u, WrapMode wrap_v) const;

 private:
  RgbImage pixels_;
};

}  // namespace candela
