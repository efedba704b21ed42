#include "validate/image_comparison.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "camera/tone_map.h"
#include "io/image_writer.h"
#include "math/srgb.h"
#include "scratch_directory.h"

namespace candela {
namespace {

// A 2×2 image and a reference that differ in two pixels:
//   (1, 0): A (0.2, 0.5, 0.2), B (0.2, 0.2, 0.2)  → G differs by 0.3 (the largest)
//   (0, 1): A (0, 0, 0),       B (0.1, 0.1, 0.1)  → every channel by 0.1
// The other two pixels are (1, 1, 1) in both.
struct Pair {
  Film a{2, 2}, b{2, 2};
  Pair() {
    for (Film* f : {&a, &b}) f->at(0, 0) = f->at(1, 1) = Color(1);
    a.at(1, 0) = Color(0.2, 0.5, 0.2);
    b.at(1, 0) = Color(0.2);
    a.at(0, 1) = Color(0);
    b.at(0, 1) = Color(0.1);
  }
};

TEST(ImageComparison, MetricsMatchHandComputedValues) {
  const Pair p;
  const ImageComparison r = compare_images(p.a, p.b);
  EXPECT_EQ(r.pixels_compared, 4u);
  // 12 samples: squared errors 0.09 + 3·0.01 = 0.12.
  EXPECT_NEAR(r.rmse, std::sqrt(0.12 / 12), 1e-12);
  // relative: 0.09/(0.04 + 0.01) + 3·0.01/(0.01 + 0.01) = 1.8 + 1.5 = 3.3.
  EXPECT_NEAR(r.relative_mse, 3.3 / 12, 1e-12);
  EXPECT_DOUBLE_EQ(r.peak, 1.0);
  EXPECT_NEAR(r.psnr, 20 * std::log10(1 / std::sqrt(0.01)), 1e-9);  // 20 dB
  EXPECT_NEAR(r.mean_absolute_error, (0.3 + 0.3) / 12, 1e-12);
  EXPECT_NEAR(r.max_absolute_error, 0.3, 1e-12);
  EXPECT_EQ(r.max_error_x, 1);
  EXPECT_EQ(r.max_error_y, 0);
  EXPECT_EQ(r.max_error_channel, 1);
  const double ya = (2 + luminance(Color(0.2, 0.5, 0.2)) + 0) / 4, yb = (2 + 0.2 + 0.1) / 4;
  EXPECT_NEAR(r.mean_luminance, ya, 1e-12);
  EXPECT_NEAR(r.mean_luminance_reference, yb, 1e-12);
  EXPECT_NEAR(r.luminance_ratio, ya / yb, 1e-12);
}

TEST(ImageComparison, IdenticalImagesHaveNoError) {
  const Pair p;
  const ImageComparison r = compare_images(p.b, p.b);
  EXPECT_EQ(r.rmse, 0);
  EXPECT_EQ(r.relative_mse, 0);
  EXPECT_EQ(r.max_absolute_error, 0);
  EXPECT_TRUE(std::isinf(r.psnr) && r.psnr > 0);
  EXPECT_EQ(r.luminance_ratio, 1);
  const nlohmann::json json = r.to_json();
  EXPECT_EQ(json["psnr_db"], "inf");
  EXPECT_EQ(json["luminance_ratio"], 1.0);
  const Film black(3, 1);
  EXPECT_EQ(compare_images(black, black).luminance_ratio, 1);  // 0/0 reads as 1
}

TEST(ImageComparison, MaskExcludesPixels) {
  const Pair p;
  // Only (1, 0) and (1, 1): the 0.3 error in G, nothing else.
  const std::vector<uint8_t> mask = {0, 1, 0, 1};
  const ImageComparison r = compare_images(p.a, p.b, &mask);
  EXPECT_EQ(r.pixels_compared, 2u);
  EXPECT_NEAR(r.rmse, std::sqrt(0.09 / 6), 1e-12);
  EXPECT_NEAR(r.max_absolute_error, 0.3, 1e-12);
  // Leaving out the differing pixels gives identical images.
  const std::vector<uint8_t> same = {1, 0, 0, 1};
  EXPECT_EQ(compare_images(p.a, p.b, &same).rmse, 0);
  const std::vector<uint8_t> none = {0, 0, 0, 0};
  EXPECT_THROW(compare_images(p.a, p.b, &none), std::invalid_argument);
  const std::vector<uint8_t> short_mask = {1};
  EXPECT_THROW(compare_images(p.a, p.b, &short_mask), std::invalid_argument);
}

TEST(ImageComparison, MaskFromImageThresholdsLuminanceAtHalf) {
  Film m(4, 1);
  m.at(0, 0) = Color(0);
  m.at(1, 0) = Color(0.5);  // not above: excluded
  m.at(2, 0) = Color(0.51);
  m.at(3, 0) = Color(0, 1, 0);  // Y 0.7152
  EXPECT_EQ(mask_from_image(m), (std::vector<uint8_t>{0, 0, 1, 1}));
}

TEST(ImageComparison, DifferentSizesAreRefusedNamingBoth) {
  try {
    compare_images(Film(3, 2), Film(2, 3));
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("3x2"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("2x3"), std::string::npos) << e.what();
  }
  EXPECT_THROW(difference_values(Film(3, 2), Film(2, 3), DifferenceMetric::absolute), std::invalid_argument);
}

TEST(ImageComparison, DifferenceValuesPerMetric) {
  Film a(3, 1), b(3, 1);
  a.at(0, 0) = Color(0.5);
  b.at(0, 0) = Color(0.25);
  a.at(1, 0) = Color(0.1);
  b.at(1, 0) = Color(0.3);
  const std::vector<double> absolute = difference_values(a, b, DifferenceMetric::absolute);
  EXPECT_NEAR(absolute[0], 0.25, 1e-12);
  EXPECT_NEAR(absolute[1], 0.2, 1e-12);
  EXPECT_EQ(absolute[2], 0);
  const std::vector<double> relative = difference_values(a, b, DifferenceMetric::relative);
  EXPECT_NEAR(relative[0], 0.25 / 0.26, 1e-12);
  EXPECT_NEAR(relative[1], 0.2 / 0.31, 1e-12);
  const std::vector<double> signed_values = difference_values(a, b, DifferenceMetric::signed_difference);
  EXPECT_NEAR(signed_values[0], 0.25, 1e-12);
  EXPECT_NEAR(signed_values[1], -0.2, 1e-12);
  const std::vector<uint8_t> mask = {1, 0, 1};
  const std::vector<double> masked = difference_values(a, b, DifferenceMetric::absolute, &mask);
  EXPECT_TRUE(std::isnan(masked[1]));
  EXPECT_NEAR(masked[0], 0.25, 1e-12);
}

TEST(ImageComparison, ReadsPngAsDecodedSrgbAndPfmAsStored) {
  const testing::ScratchDirectory directory("candela-image-comparison");
  Film film(2, 1);
  film.at(0, 0) = Color(0.5, 0.25, 1.0);
  film.at(1, 0) = Color(0.0, 0.75, 0.125);
  const std::string pfm = (directory.path() / "a.pfm").string();
  const std::string png = (directory.path() / "a.png").string();
  write_image(film, pfm, DisplaySettings{});
  write_image(film, png, DisplaySettings{});
  const LinearImage from_pfm = read_linear_image(pfm);
  EXPECT_FALSE(from_pfm.srgb_decoded);
  ASSERT_EQ(from_pfm.film.width(), 2);
  ASSERT_EQ(from_pfm.film.height(), 1);
  EXPECT_EQ(from_pfm.film.at(0, 0), film.at(0, 0));
  EXPECT_EQ(from_pfm.film.at(1, 0), film.at(1, 0));
  const LinearImage from_png = read_linear_image(png);
  EXPECT_TRUE(from_png.srgb_decoded);
  for (int x = 0; x < 2; ++x)
    for (int c = 0; c < 3; ++c) {
      // The 8-bit code the writer chose, decoded: within half a code step of the original.
      const double code = std::round(srgb_encode(film.at(x, 0)[c]) * 255);
      EXPECT_NEAR(from_png.film.at(x, 0)[c], srgb_decode(code / 255), 1e-6) << x << " " << c;
    }
  EXPECT_THROW(read_linear_image((directory.path() / "missing.png").string()), std::runtime_error);
}

}  // namespace
}  // namespace candela
