// Error metrics between an image A and a reference B (`candela compare A B`, SPEC "Product
// surface"), over the pixels a mask includes and the three channels, on linear RGB:
//   rmse                 sqrt(mean (a − b)²)
//   relative_mse         mean (a − b)² / (b² + ε) with ε = kRelativeMseEpsilon = 1e-2, B the
//                        reference: the relMSE of the pbrt / Mitsuba denoising and rendering papers
//                        (the ε keeps dark reference pixels from dominating)
//   psnr                 20·log10(peak / rmse) dB with peak = the reference's largest channel value
//                        over the included pixels (1 for an 8-bit image with a white pixel); +inf
//                        when rmse = 0; −inf when rmse > 0 and the reference is black (peak 0)
//   mean_absolute_error  mean |a − b|
//   max_absolute_error   max |a − b|, at pixel (x, y) (y = 0 the top row), channel 0 R, 1 G, 2 B;
//                        the first such sample in row order when several tie
//   mean luminance       of A and of B, Rec. 709 Y = 0.2126 R + 0.7152 G + 0.0722 B, and their
//                        ratio A/B (1 when both are 0, +inf when only B's is 0)
// Sums are accumulated in double, pixel by pixel in row order: the results are deterministic.
#pragma once

#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "camera/film.h"

namespace candela {

inline constexpr double kRelativeMseEpsilon = 1e-2;
// A mask pixel includes its image pixel when its (linear, decoded) luminance is above this.
inline constexpr double kMaskThreshold = 0.5;

struct ImageComparison {
  int width = 0, height = 0;
  std::size_t pixels_compared = 0;  // pixels the mask includes (all without a mask)
  double rmse = 0;
  double relative_mse = 0;
  double psnr = 0;
  double peak = 0;  // the reference's largest channel value, PSNR's peak
  double mean_absolute_error = 0;
  double max_absolute_error = 0;
  int max_error_x = 0, max_error_y = 0, max_error_channel = 0;
  double mean_luminance = 0;            // of A
  double mean_luminance_reference = 0;  // of B
  double luminance_ratio = 1;           // A / B

  // Every field; infinite values (psnr, luminance_ratio) as the strings "inf" / "-inf".
  nlohmann::json to_json() const;
};

// mask: null, or width·height bytes, row by row from the top, non-zero where the pixel counts.
// Throws std::invalid_argument when the sizes differ (naming both) or the mask excludes every
// pixel.
ImageComparison compare_images(const Film& image, const Film& reference,
                               const std::vector<uint8_t>* mask = nullptr);

// 1 where the mask image's luminance is above kMaskThreshold, else 0.
std::vector<uint8_t> mask_from_image(const Film& mask);

// What a difference picture shows per pixel, from the luminances Y_A and Y_B:
enum class DifferenceMetric {
  absolute,           // |Y_A − Y_B|
  relative,           // |Y_A − Y_B| / (|Y_B| + kRelativeMseEpsilon)
  signed_difference,  // Y_A − Y_B
};

// Per-pixel values for io/false_color.h, row by row from the top; NaN where the mask excludes
// the pixel. The sizes must agree (std::invalid_argument otherwise).
std::vector<double> difference_values(const Film& image, const Film& reference, DifferenceMetric metric,
                                      const std::vector<uint8_t>* mask = nullptr);

// A rendered image as its luminance in cd/m², grey: efficacy × Y / π per pixel (a
// rendered value is π × the radiance; Y Rec. 709; the efficacy of shading/photometric_units.h by
// default) — what compare --luminance and report --luminance measure.
Film luminance_film(const Film& image, double efficacy);

// An image file as linear RGB: 8- and 16-bit formats (PNG, JPG, ...) decoded from sRGB, EXR, PFM
// and HDR taken as stored (shading/texture_image.h reads them). Throws std::runtime_error naming
// the file.
struct LinearImage {
  Film film{0, 0};
  bool srgb_decoded = false;  // the file held sRGB-encoded integers
};
LinearImage read_linear_image(const std::string& path);

}  // namespace candela
