// The check every written image passes (no non-finite pixels from legal values).
#include "io/image_writer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <string>

#include "io/image_reader.h"
#include "scratch_directory.h"

namespace candela {
namespace {

TEST(ImageWriter, PixelsThatAreNotFiniteOrBeyondAFloatAreNamedAndNotWritten) {
  Film film(4, 3);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 4; ++x) film.at(x, y) = Color(0.5);
  EXPECT_EQ(non_finite_image_problem(film, ImageFormat::png, 0), "");
  EXPECT_EQ(non_finite_image_problem(film, ImageFormat::pfm, 64), "");  // 0.5 · 2^64: a float holds it

  film.at(2, 1) = Color(1, std::nan(""), 1);
  film.at(3, 2) = Color(HUGE_VAL, 0, 0);
  for (const ImageFormat format : {ImageFormat::png, ImageFormat::exr, ImageFormat::pfm}) {
    const std::string problem = non_finite_image_problem(film, format, 0);
    EXPECT_NE(problem.find("the image has 2 pixels that are not finite (first at pixel (2, 1): (1, nan, 1))"),
              std::string::npos)
        << problem;
  }

  Film bright(2, 2);
  bright.at(1, 1) = Color(1e30, 0, 0);  // finite; 1e30 · 2^30 ≈ 1.1e39 is beyond a float
  EXPECT_EQ(non_finite_image_problem(bright, ImageFormat::pfm, 20), "");
  EXPECT_EQ(non_finite_image_problem(bright, ImageFormat::png, 30), "");  // PNG tone-maps doubles
  const std::string problem = non_finite_image_problem(bright, ImageFormat::exr, 30);
  EXPECT_NE(problem.find("1 pixel beyond the largest single-precision float (3.4e38) once film.exposure (30 "
                         "stops) is applied (first at pixel (1, 1): (1e+30, 0, 0))"),
            std::string::npos)
      << problem;

  const testing::ScratchDirectory scratch("candela-image-writer");
  const std::string path = (scratch.path() / "bright.exr").string();
  DisplaySettings display;
  display.exposure = 30;
  EXPECT_THROW(write_image(bright, path, display), std::runtime_error);
  EXPECT_TRUE(std::filesystem::is_empty(scratch.path()));  // nothing, not even a temporary
}

// -o out.hdr and candela convert write Radiance RGBE. Values whose mantissas fit 8 bits
// come back exactly; the others within RGBE's step (2^e / 256, at most 1/128 of the largest channel);
// negative values, which RGBE cannot hold, as 0; the top row of the film is the file's first.
TEST(ImageWriter, RadianceHdrKeepsLinearValuesWithinItsEightBitMantissas) {
  Film film(9, 2);  // 9 wide: stb run-length encodes rows of 8 pixels or more
  for (int x = 0; x < 9; ++x) {
    film.at(x, 0) = Color(0.5, 2, 16);  // shared exponent 5: 4, 16, 128 of 256
    film.at(x, 1) = Color(0.3 * (x + 1), -0.25, 1e-3);
  }
  const testing::ScratchDirectory scratch("candela-image-writer-hdr");
  const std::string path = (scratch.path() / "film.hdr").string();
  DisplaySettings display;
  display.exposure = 1;  // doubles every value, as for .exr and .pfm
  write_image(film, path, display);
  const RgbImage image = read_image(path);
  ASSERT_EQ(image.width(), 9);
  ASSERT_EQ(image.height(), 2);
  for (int x = 0; x < 9; ++x) {
    EXPECT_EQ(image.texel(x, 1), Color(1, 4, 32)) << x;  // read_image's y = 0 is the bottom row
    const Color bottom = image.texel(x, 0);
    const double largest = 0.6 * (x + 1);
    EXPECT_NEAR(bottom.r, largest, largest / 128) << x;
    EXPECT_EQ(bottom.g, 0) << x;
    EXPECT_NEAR(bottom.b, 2e-3, largest / 128) << x;
  }
}

}  // namespace
}  // namespace candela
