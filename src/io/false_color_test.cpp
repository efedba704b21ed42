#include "io/false_color.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "camera/tone_map.h"
#include "io/image_reader.h"
#include "io/image_writer.h"
#include "scratch_directory.h"

namespace candela {
namespace {

void expect_color_near(const Color& actual, const Color& expected, double tolerance) {
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(actual[c], expected[c], tolerance) << "channel " << c;
}

Color display(const Color& linear) {
  return {srgb_encode(linear.r), srgb_encode(linear.g), srgb_encode(linear.b)};
}

TEST(FalseColor, ViridisEndpointsMatchThePublishedMap) {
  // matplotlib's viridis: #440154 at 0, #21918c at 0.5, #fde725 at 1.
  expect_color_near(color_map_viridis(0), Color(0x44, 0x01, 0x54) / 255.0, 0.02);
  expect_color_near(color_map_viridis(0.5), Color(0x21, 0x91, 0x8c) / 255.0, 0.02);
  expect_color_near(color_map_viridis(1), Color(0xfd, 0xe7, 0x25) / 255.0, 0.02);
  // Clamped outside [0, 1]; NaN reads as 0.
  EXPECT_EQ(color_map_viridis(-3), color_map_viridis(0));
  EXPECT_EQ(color_map_viridis(7), color_map_viridis(1));
  EXPECT_EQ(color_map_viridis(std::numeric_limits<double>::quiet_NaN()), color_map_viridis(0));
  // Luminance rises monotonically (a perceptual map).
  for (int i = 1; i <= 100; ++i)
    EXPECT_GT(luminance(color_map_viridis(i / 100.0)), luminance(color_map_viridis((i - 1) / 100.0))) << i;
}

TEST(FalseColor, DivergingIsBlueWhiteRed) {
  const Color blue = color_map_diverging(0), white = color_map_diverging(0.5), red = color_map_diverging(1);
  EXPECT_GT(blue.b, blue.r);
  EXPECT_EQ(white, Color(1));
  EXPECT_GT(red.r, red.b);
  EXPECT_EQ(color_map(ColorMap::diverging, 0.25), color_map_diverging(0.25));
  EXPECT_EQ(color_map(ColorMap::viridis, 0.25), color_map_viridis(0.25));
}

TEST(FalseColor, FormatsScaleValuesCompactly) {
  EXPECT_EQ(format_scale_value(0), "0");
  EXPECT_EQ(format_scale_value(0.0123), "0.0123");
  EXPECT_EQ(format_scale_value(0.5), "0.5");
  EXPECT_EQ(format_scale_value(-2), "-2");
  EXPECT_EQ(format_scale_value(1.234e-5), "1.23e-05");
  EXPECT_EQ(format_scale_value(12345), "1.23e+04");
}

TEST(FalseColor, ImageHasTheBarBelowWithTheMapsEndColors) {
  constexpr int width = 200, height = 10;
  std::vector<double> values(std::size_t(width) * height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) values[std::size_t(y) * width + x] = x * 0.01;  // 0 .. 1.99
  values[5] = std::numeric_limits<double>::quiet_NaN();                             // no data at (5, 0)
  const Film film = false_color_image(values, width, height, 0.0, 1.0, ColorMap::viridis);
  ASSERT_EQ(film.width(), width);
  ASSERT_EQ(film.height(), height + color_bar_height(width));
  // Pixels: the map at (value − low)/(high − low), clamped; NaN grey. Linear in the Film.
  expect_color_near(display(film.at(0, 3)), color_map_viridis(0), 1e-9);
  expect_color_near(display(film.at(50, 3)), color_map_viridis(0.5), 1e-9);
  expect_color_near(display(film.at(150, 3)), color_map_viridis(1), 1e-9);
  expect_color_near(display(film.at(5, 0)), Color(kNoDataGrey), 1e-9);
  // The bar: its first and last columns are the map's ends; the row above it is background.
  const int bar_row = height + 3 + 8;
  expect_color_near(display(film.at(0, bar_row)), color_map_viridis(0), 1e-9);
  expect_color_near(display(film.at(width - 1, bar_row)), color_map_viridis(1), 1e-9);
  EXPECT_EQ(film.at(width / 2, height), Color(0));
  // Labels are drawn in white (anti-aliased DejaVu Sans) somewhere under the bar.
  int white = 0;
  for (int y = height + 3 + 16; y < film.height(); ++y)
    for (int x = 0; x < width; ++x) white += film.at(x, y).g > 0.5;
  EXPECT_GT(white, 30);
}

// Radiance falsecolor's -log and -cl: a logarithmic scale puts each decade at the same step of
// the map, and n contour steps draw black iso-lines where neighbouring pixels change step.
TEST(FalseColor, LogarithmicScaleAndContours) {
  FalseColorScale log_scale;
  log_scale.low = 1;
  log_scale.high = 1000;
  log_scale.logarithmic = true;
  EXPECT_NEAR(log_scale.position(10), 1.0 / 3, 1e-12);
  EXPECT_NEAR(log_scale.position(100), 2.0 / 3, 1e-12);
  EXPECT_EQ(log_scale.position(0.5), 0);
  EXPECT_EQ(log_scale.position(-3), 0);
  EXPECT_EQ(log_scale.position(5000), 1);
  EXPECT_TRUE(std::isnan(log_scale.position(std::nan(""))));
  FalseColorScale linear;
  linear.low = 2;
  linear.high = 6;
  EXPECT_NEAR(linear.position(3), 0.25, 1e-15);

  // A ramp 0 .. 1 along x in 4 contour steps: lines at the three step boundaries only.
  constexpr int width = 100, height = 6;
  std::vector<double> values(std::size_t(width) * height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) values[std::size_t(y) * width + x] = (x + 0.5) / width;
  FalseColorScale banded;
  banded.contours = 4;
  const Film film = false_color_image(values, width, height, banded, ColorMap::viridis);
  std::vector<int> line_columns;
  for (int x = 0; x < width; ++x)
    if (film.at(x, 2) == Color(0)) line_columns.push_back(x);
  EXPECT_EQ(line_columns, (std::vector<int>{24, 49, 74}));
  expect_color_near(display(film.at(10, 2)), color_map_viridis(0.105), 1e-9);
  // Without contours the same ramp has no black pixel.
  const Film plain = false_color_image(values, width, height, 0.0, 1.0, ColorMap::viridis);
  for (int x = 0; x < width; ++x) EXPECT_NE(plain.at(x, 2), Color(0)) << x;

  FalseColorScale bad = log_scale;
  bad.low = 0;
  EXPECT_THROW(false_color_image({1}, 1, 1, bad, ColorMap::viridis), std::invalid_argument);
  FalseColorScale too_many;
  too_many.contours = 1000;
  EXPECT_THROW(false_color_image({1}, 1, 1, too_many, ColorMap::viridis), std::invalid_argument);
}

TEST(FalseColor, PngKeepsTheMapsColors) {
  const testing::ScratchDirectory directory("candela-false-color");
  const std::vector<double> values = {-1, 0, 1, 0.5};
  const Film film = false_color_image(values, 4, 1, -1, 1, ColorMap::diverging);
  const std::string path = (directory.path() / "map.png").string();
  write_image(film, path, DisplaySettings{});
  const RgbImage png = read_image(path, ColorEncoding::linear);  // the stored codes / 255
  ASSERT_EQ(png.width(), 4);
  ASSERT_EQ(png.height(), 1 + color_bar_height(4));
  const int top = png.height() - 1;  // RgbImage counts rows from the bottom
  for (int x = 0; x < 4; ++x)
    expect_color_near(png.texel(x, top), color_map_diverging((values[std::size_t(x)] + 1) / 2),
                      0.5 / 255 + 1e-6);
}

TEST(FalseColor, RefusesBadArguments) {
  EXPECT_THROW(false_color_image({1, 2}, 3, 1, 0, 1, ColorMap::viridis), std::invalid_argument);
  EXPECT_THROW(false_color_image({1}, 1, 1, 1, 1, ColorMap::viridis), std::invalid_argument);
  EXPECT_THROW(false_color_image({1}, 1, 1, 0, std::numeric_limits<double>::infinity(), ColorMap::viridis),
               std::invalid_argument);
  EXPECT_THROW(false_color_image({}, 0, 0, 0, 1, ColorMap::viridis), std::invalid_argument);
  // A one-pixel image still gets its bar (labels that do not fit are left out).
  const Film tiny = false_color_image({0.5}, 1, 1, 0, 1, ColorMap::viridis);
  EXPECT_EQ(tiny.height(), 1 + color_bar_height(1));
}

// The bar's labels are DejaVu Sans, whole or not at all (smaller when the low label is
// wider than the picture, left out below 5 pixels), and a quantity gets a caption line with the
// unit: "illuminance (lx)", the labels then bare numbers.
TEST(FalseColor, LabelsAreWholeOrAbsentAndTheCaptionNamesTheQuantityAndUnit) {
  const auto white_columns = [](const Film& film, int row0, int row1) {
    std::vector<int> columns;
    for (int x = 0; x < film.width(); ++x)
      for (int y = row0; y < row1; ++y)
        if (film.at(x, y).r > 0.5 && film.at(x, y).g > 0.5 && film.at(x, y).b > 0.5) {
          columns.push_back(x);
          break;
        }
    return columns;
  };
  constexpr int width = 300, height = 4;
  const std::vector<double> values(std::size_t(width) * height, 0.5);
  const FalseColorScale plain = false_color_scale(600, {}, false, 0, "lx");
  const FalseColorScale captioned = false_color_scale(600, {}, false, 0, "lx", "illuminance");
  const Film without = false_color_image(values, width, height, plain, ColorMap::viridis);
  const Film with = false_color_image(values, width, height, captioned, ColorMap::viridis);
  EXPECT_EQ(without.height(), height + color_bar_height(width, false));
  EXPECT_EQ(with.height(), height + color_bar_height(width, true));
  EXPECT_GT(color_bar_height(width, true), color_bar_height(width, false) + 10);
  // Below the ticks: "0 lx" at the left, "600 lx" at the right, "300 lx" in the middle.
  const int labels_top = height + 3 + 16 + 3;
  const std::vector<int> labels = white_columns(without, labels_top, without.height());
  ASSERT_FALSE(labels.empty());
  EXPECT_LT(labels.front(), 3);
  EXPECT_GT(labels.back(), width - 4);
  // The caption's line: centred text; the bare numbers above it are narrower than with "lx".
  const int caption_top = height + color_bar_height(width, false) - 3;
  const std::vector<int> caption = white_columns(with, caption_top, with.height());
  ASSERT_FALSE(caption.empty());
  EXPECT_NEAR((caption.front() + caption.back()) / 2.0, width / 2.0, 4);
  EXPECT_GT(caption.front(), 60);  // "illuminance (lx)" is about 110 pixels at 14
  // Too narrow for even a shrunk label: none is drawn, rather than a part of one.
  const FalseColorScale tiny_scale = false_color_scale(1.234e-5, {1.234e-5, 2e-5}, false, 0, "lx");
  const Film narrow =
      false_color_image({1.5e-5, 1.5e-5, 1.5e-5, 1.5e-5}, 4, 1, tiny_scale, ColorMap::viridis);
  const std::vector<int> drawn = white_columns(narrow, 1 + 3 + 16 + 3, narrow.height());
  EXPECT_TRUE(drawn.empty()) << drawn.size();
}

}  // namespace
}  // namespace candela
