// Texture lookups (SPEC §7: image textures, bilinear): the bottom-row-first convention,
// bilinear lookups and wrap modes. Decoding files is io's (src/io/image_reader_test.cpp).
#include "shading/texture_image.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "camera/film.h"
#include "io/image_writer.h"
#include "scratch_directory.h"
#include "shading/image_texture.h"

namespace candela {
namespace {

// 4×2, texel (x, y) = (x + 4y, 10x, 100y): every texel different, averages exact.
TextureImage grid_image() {
  std::vector<float> rgb;
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 4; ++x)
      for (const int value : {x + 4 * y, 10 * x, 100 * y}) rgb.push_back(static_cast<float>(value));
  return TextureImage(4, 2, std::move(rgb));
}

constexpr WrapMode kWrapModes[] = {WrapMode::repeat, WrapMode::clamp, WrapMode::mirror};

TEST(TextureImage, ConstructorKeepsBottomRowFirstAndChecksSizes) {
  const TextureImage image = grid_image();
  EXPECT_EQ(image.texel(0, 0), Color(0, 0, 0));
  EXPECT_EQ(image.texel(3, 0), Color(3, 30, 0));
  EXPECT_EQ(image.texel(2, 1), Color(6, 20, 100));
  EXPECT_THROW(TextureImage(4, 2, std::vector<float>(23)), std::invalid_argument);
  EXPECT_THROW(TextureImage(0, 2, {}), std::invalid_argument);
  EXPECT_THROW(TextureImage(-1, -1, std::vector<float>(3)), std::invalid_argument);
}

TEST(TextureImage, BilinearAtTexelCentresGivesTheTexels) {
  const TextureImage image = grid_image();
  for (const WrapMode wrap : kWrapModes)
    for (int y = 0; y < 2; ++y)
      for (int x = 0; x < 4; ++x)
        EXPECT_EQ(image.bilinear({(x + 0.5) / 4, (y + 0.5) / 2}, wrap), image.texel(x, y))
            << kWrapModeNames.name(wrap) << " " << x << ", " << y;
}

TEST(TextureImage, BilinearHalfwayIsTheAverage) {
  const TextureImage image = grid_image();
  for (const WrapMode wrap : kWrapModes) {
    // Between texels (1, 0) and (2, 0): u = 0.5, v = 0.25.
    EXPECT_EQ(image.bilinear({0.5, 0.25}, wrap), (image.texel(1, 0) + image.texel(2, 0)) * 0.5);
    // Between the rows: v = 0.5.
    EXPECT_EQ(image.bilinear({0.125, 0.5}, wrap), (image.texel(0, 0) + image.texel(0, 1)) * 0.5);
    // Amid four texels.
    EXPECT_EQ(image.bilinear({0.75, 0.5}, wrap),
              (image.texel(2, 0) + image.texel(3, 0) + image.texel(2, 1) + image.texel(3, 1)) * 0.25);
    // A quarter of the way from (0, 1) to (1, 1).
    EXPECT_EQ(image.bilinear({0.1875, 0.75}, wrap), image.texel(0, 1) * 0.75 + image.texel(1, 1) * 0.25);
  }
}

TEST(TextureImage, RepeatBlendsTheLastAndFirstColumnsAcrossTheSeam) {
  const TextureImage image = grid_image();
  const Color seam = (image.texel(3, 0) + image.texel(0, 0)) * 0.5;
  EXPECT_EQ(image.bilinear({0.0, 0.25}, WrapMode::repeat), seam);
  EXPECT_EQ(image.bilinear({1.0, 0.25}, WrapMode::repeat), seam);
  EXPECT_EQ(image.bilinear({-3.0, 0.25}, WrapMode::repeat), seam);
  // Whole periods away, the same texel.
  EXPECT_EQ(image.bilinear({1.125, 0.25}, WrapMode::repeat), image.texel(0, 0));
  EXPECT_EQ(image.bilinear({-0.875, 0.25}, WrapMode::repeat), image.texel(0, 0));
  EXPECT_EQ(image.bilinear({0.375, 1.75}, WrapMode::repeat), image.texel(1, 1));
  // The v seam blends the top and bottom rows.
  EXPECT_EQ(image.bilinear({0.125, 0.0}, WrapMode::repeat), (image.texel(0, 1) + image.texel(0, 0)) * 0.5);
}

TEST(TextureImage, ClampHoldsTheEdgeTexels) {
  const TextureImage image = grid_image();
  EXPECT_EQ(image.bilinear({0.0, 0.25}, WrapMode::clamp), image.texel(0, 0));
  EXPECT_EQ(image.bilinear({-5.0, 0.25}, WrapMode::clamp), image.texel(0, 0));
  EXPECT_EQ(image.bilinear({1.0, 0.25}, WrapMode::clamp), image.texel(3, 0));
  EXPECT_EQ(image.bilinear({7.0, 3.0}, WrapMode::clamp), image.texel(3, 1));
  EXPECT_EQ(image.bilinear({-1.0, -1.0}, WrapMode::clamp), image.texel(0, 0));
  // Inside the outer half texel, the edge texel alone.
  EXPECT_EQ(image.bilinear({0.05, 0.25}, WrapMode::clamp), image.texel(0, 0));
}

TEST(TextureImage, MirrorReflectsAtEveryInteger) {
  const TextureImage image = grid_image();
  EXPECT_EQ(image.bilinear({-0.125, 0.25}, WrapMode::mirror), image.texel(0, 0));  // reflection of 0.125
  EXPECT_EQ(image.bilinear({1.125, 0.25}, WrapMode::mirror), image.texel(3, 0));   // of 0.875
  EXPECT_EQ(image.bilinear({1.375, 0.25}, WrapMode::mirror), image.texel(2, 0));   // of 0.625
  EXPECT_EQ(image.bilinear({2.125, 0.25}, WrapMode::mirror), image.texel(0, 0));   // a full period on
  EXPECT_EQ(image.bilinear({-1.125, 0.25}, WrapMode::mirror), image.texel(3, 0));  // of −0.875, of 0.875
  // At the mirror line the edge texel meets its own reflection.
  EXPECT_EQ(image.bilinear({1.0, 0.25}, WrapMode::mirror), image.texel(3, 0));
  EXPECT_EQ(image.bilinear({0.0, 0.25}, WrapMode::mirror), image.texel(0, 0));
  EXPECT_EQ(image.bilinear({0.125, 1.25}, WrapMode::mirror), image.texel(0, 1));  // v: of 0.75
  // Per-axis modes.
  EXPECT_EQ(image.bilinear({1.125, 1.25}, WrapMode::repeat, WrapMode::mirror), image.texel(0, 1));
}

TEST(TextureImage, NonFiniteAndHugeCoordinatesStayInside) {
  const TextureImage image = grid_image();
  for (const WrapMode wrap : kWrapModes) {
    EXPECT_EQ(image.bilinear({std::nan(""), 0.25}, wrap), image.bilinear({0.0, 0.25}, wrap));
    EXPECT_EQ(image.bilinear({0.125, INFINITY}, wrap), image.bilinear({0.125, 0.0}, wrap));
    const Color far = image.bilinear({1e300, -1e300}, wrap);
    EXPECT_TRUE(std::isfinite(far.r) && far.r >= 0 && far.r <= 7) << kWrapModeNames.name(wrap);
  }
}

TEST(ImageTexture, LookupIsTheMultiplierTimesTheBilinearValue) {
  auto image = std::make_shared<const TextureImage>(grid_image());
  const ImageTexture texture(image, WrapMode::clamp, Color(2, 0.5, 1), std::make_shared<ParametricMapping>());
  EXPECT_EQ(texture.type_name(), "image");
  EXPECT_EQ(texture.lookup({0.5, 0.25}), Color(2, 0.5, 1) * image->bilinear({0.5, 0.25}, WrapMode::clamp));
  SurfaceHit hit;
  hit.uv = {0.625, 0.75};  // texel (2, 1) = (6, 20, 100)
  EXPECT_EQ(texture.evaluate(hit), Color(12, 10, 100));
  EXPECT_DOUBLE_EQ(texture.evaluate_scalar(hit), (12.0 + 10 + 100) / 3);
  // The wrap mode is the texture's.
  const ImageTexture repeating(image, WrapMode::repeat, Color(1), std::make_shared<ParametricMapping>());
  EXPECT_EQ(repeating.lookup({0.0, 0.25}), (image->texel(3, 0) + image->texel(0, 0)) * 0.5);
  EXPECT_EQ(repeating.wrap(), WrapMode::repeat);
  EXPECT_THROW(ImageTexture(nullptr, WrapMode::repeat, Color(1), std::make_shared<ParametricMapping>()),
               std::invalid_argument);
  EXPECT_THROW(ImageTexture(image, WrapMode::repeat, Color(1), nullptr), std::invalid_argument);
}

// A little-endian colour PFM of one row (PFM rows run bottom first; one row has no order).
std::string write_pfm_row(const std::filesystem::path& file, const std::vector<float>& rgb) {
  std::ofstream out(file, std::ios::binary);
  out << "PF\n" << rgb.size() / 3 << " 1\n-1.0\n";
  for (const float value : rgb) {
    char bytes[4];
    std::memcpy(bytes, &value, 4);  // the test machines are little-endian, as the header says
    out.write(bytes, 4);
  }
  return file.string();
}

std::string load_error(const std::string& file) {
  try {
    (void)TextureImage::load(file);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  ADD_FAILURE() << "no error for " << file;
  return "";
}

// A PFM texel of 3e38 (finite) made infinite pixels once multiplied by a light and
// written as float. Texels above TextureImage::kMaxValue, and NaN or infinite ones, are refused
// naming the file and the first bad texel; the limit itself loads, and read_image without a
// limit (`candela compare` reads renders through it) still reads the large value.
TEST(TextureImage, LoadRefusesTexelsAboveTheLimitNamingTheFileAndTexel) {
  candela::testing::ScratchDirectory scratch("candela-texture-limit");
  const std::string huge = write_pfm_row(scratch.path() / "huge.pfm", {1, 2, 3, 4, 5, 3e38f});
  std::string message = load_error(huge);
  EXPECT_NE(message.find(huge), std::string::npos) << message;
  EXPECT_NE(
      message.find("texel (1, 0) counted from the bottom-left, channel 2 (blue), is 3e+38, above the limit "
                   "of 1e+06"),
      std::string::npos)
      << message;
  EXPECT_EQ(read_image(huge).texel(1, 0).b, 3e38f);

  const std::string negative = write_pfm_row(scratch.path() / "negative.pfm", {-2e6f, 0, 0});
  EXPECT_NE(load_error(negative).find("channel 0 (red), is -2000000"), std::string::npos);

  const std::string nan =
      write_pfm_row(scratch.path() / "nan.pfm", {0, std::numeric_limits<float>::quiet_NaN(), 0, 1, 1, 1});
  message = load_error(nan);
  EXPECT_NE(message.find("texel (0, 0) counted from the bottom-left, channel 1 (green), is NaN"),
            std::string::npos)
      << message;

  const std::string limit = write_pfm_row(scratch.path() / "limit.pfm", {1e6f, 0, -1e6f});
  EXPECT_EQ(TextureImage::load(limit).texel(0, 0), Color(1e6, 0, -1e6));

  // EXR (and Radiance HDR) values go through the same check: the largest float is refused.
  Film film(1, 1);
  film.at(0, 0) = Color(0, std::numeric_limits<float>::max(), 0);
  const std::string exr = (scratch.path() / "huge.exr").string();
  write_exr(film, exr, 0);
  EXPECT_NE(load_error(exr).find("channel 1 (green), is 3.4028235e+38"), std::string::npos)
      << load_error(exr);
}

}  // namespace
}  // namespace candela
