#include "validate/image_comparison.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <limits>
#include <stdexcept>

#include "io/image_reader.h"
#include "math/constants.h"
#include "util/file_extension.h"

namespace candela {

namespace {

void check_same_size(const Film& image, const Film& reference) {
  if (image.width() != reference.width() || image.height() != reference.height())
    throw std::invalid_argument(fmt::format("the images differ in size: {}x{} and {}x{} (reference)",
                                            image.width(), image.height(), reference.width(),
                                            reference.height()));
}

void check_mask(const Film& image, const std::vector<uint8_t>* mask) {
  if (mask && mask->size() != image.pixels().size())
    throw std::invalid_argument(
        fmt::format("the mask has {} pixels, the images {}x{}", mask->size(), image.width(), image.height()));
}

nlohmann::json number_or_text(double value) {
  if (std::isfinite(value)) return value;
  if (std::isnan(value)) return "nan";
  return value > 0 ? "inf" : "-inf";
}

}  // namespace

nlohmann::json ImageComparison::to_json() const {
  return {
      {"width", width},
      {"height", height},
      {"pixels_compared", pixels_compared},
      {"rmse", rmse},
      {"relative_mse", relative_mse},
      {"relative_mse_epsilon", kRelativeMseEpsilon},
      {"psnr_db", number_or_text(psnr)},
      {"psnr_peak", peak},
      {"mean_absolute_error", mean_absolute_error},
      {"max_absolute_error", max_absolute_error},
      {"max_absolute_error_at", {{"x", max_error_x}, {"y", max_error_y}, {"channel", max_error_channel}}},
      {"mean_luminance", mean_luminance},
      {"mean_luminance_reference", mean_luminance_reference},
      {"luminance_ratio", number_or_text(luminance_ratio)},
  };
}

ImageComparison compare_images(const Film& image, const Film& reference, const std::vector<uint8_t>* mask) {
  check_same_size(image, reference);
  check_mask(image, mask);
  ImageComparison result;
  result.width = image.width();
  result.height = image.height();
  double squared = 0, relative = 0, absolute = 0, luminance_a = 0, luminance_b = 0;
  result.max_absolute_error = -1;
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) {
      const std::size_t index = std::size_t(y) * std::size_t(image.width()) + std::size_t(x);
      if (mask && !(*mask)[index]) continue;
      ++result.pixels_compared;
      const Color& a = image.at(x, y);
      const Color& b = reference.at(x, y);
      for (int c = 0; c < 3; ++c) {
        const double difference = a[c] - b[c];
        squared += difference * difference;
        relative += difference * difference / (b[c] * b[c] + kRelativeMseEpsilon);
        absolute += std::abs(difference);
        if (std::abs(difference) > result.max_absolute_error) {
          result.max_absolute_error = std::abs(difference);
          result.max_error_x = x;
          result.max_error_y = y;
          result.max_error_channel = c;
        }
        result.peak = std::max(result.peak, b[c]);
      }
      luminance_a += luminance(a);
      luminance_b += luminance(b);
    }
  if (result.pixels_compared == 0)
    throw std::invalid_argument(
        fmt::format("the mask excludes all {}x{} pixels", image.width(), image.height()));
  const double samples = 3.0 * double(result.pixels_compared);
  result.rmse = std::sqrt(squared / samples);
  result.relative_mse = relative / samples;
  result.mean_absolute_error = absolute / samples;
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  if (result.rmse == 0)
    result.psnr = kInfinity;
  else if (result.peak <= 0)
    result.psnr = -kInfinity;
  else
    result.psnr = 20 * std::log10(result.peak / result.rmse);
  result.mean_luminance = luminance_a / double(result.pixels_compared);
  result.mean_luminance_reference = luminance_b / double(result.pixels_compared);
  if (result.mean_luminance_reference != 0)
    result.luminance_ratio = result.mean_luminance / result.mean_luminance_reference;
  else
    result.luminance_ratio = result.mean_luminance == 0 ? 1.0 : kInfinity;
  return result;
}

std::vector<uint8_t> mask_from_image(const Film& mask) {
  std::vector<uint8_t> included(mask.pixels().size());
  for (std::size_t i = 0; i < included.size(); ++i)
    included[i] = luminance(mask.pixels()[i]) > kMaskThreshold;
  return included;
}

std::vector<double> difference_values(const Film& image, const Film& reference, DifferenceMetric metric,
                                      const std::vector<uint8_t>* mask) {
  check_same_size(image, reference);
  check_mask(image, mask);
  std::vector<double> values(image.pixels().size());
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (mask && !(*mask)[i]) {
      values[i] = std::numeric_limits<double>::quiet_NaN();
      continue;
    }
    const double a = luminance(image.pixels()[i]), b = luminance(reference.pixels()[i]);
    switch (metric) {
      case DifferenceMetric::absolute:
        values[i] = std::abs(a - b);
        break;
      case DifferenceMetric::relative:
        values[i] = std::abs(a - b) / (std::abs(b) + kRelativeMseEpsilon);
        break;
      case DifferenceMetric::signed_difference:
        values[i] = a - b;
        break;
    }
  }
  return values;
}

LinearImage read_linear_image(const std::string& path) {
  const RgbImage texture = read_image(path, ColorEncoding::automatic);
  const std::string extension = lower_case_extension(path);
  LinearImage result;
  result.srgb_decoded =
      extension != ".exr" && extension != ".pfm" && extension != ".hdr" && extension != ".pic";
  const int width = texture.width(), height = texture.height();
  result.film = Film(width, height);
  // RgbImage rows run bottom first; Film rows top first.
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) result.film.at(x, y) = texture.texel(x, height - 1 - y);
  return result;
}

Film luminance_film(const Film& image, double efficacy) {
  Film result(image.width(), image.height());
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x)
      result.at(x, y) = Color(efficacy / kPi * luminance(image.at(x, y)));
  return result;
}

}  // namespace candela
