// Image files by extension: .png (8-bit sRGB, tone-mapped), .exr and .pfm (linear float).
#pragma once

#include <string>

#include "camera/film.h"
#include "camera/tone_map.h"

namespace candela {

enum class ImageFormat { png, exr, pfm };

// False for an extension we cannot write.
bool image_format_for_path(const std::string& path, ImageFormat& format);
// Issue 21: what makes the image unwritable, or "": a pixel that is not finite (a light, emission
// or texture value so large that the arithmetic overflowed), or — for .exr and .pfm, which store
// single-precision floats — a pixel larger than the largest float once film.exposure is applied.
// The count and the first such pixel (x, y, value) are named.
std::string non_finite_image_problem(const Film& film, ImageFormat format, double exposure);

// Writes atomically; throws std::runtime_error on an I/O failure and with non_finite_image_problem's
// message for an image that problem refuses (callers that know the scene report it as bad input
// first).
void write_image(const Film& film, const std::string& path, const DisplaySettings& display);

void write_png(const Film& film, const std::string& path, const DisplaySettings& display);
void write_exr(const Film& film, const std::string& path, double exposure);
void write_pfm(const Film& film, const std::string& path, double exposure);

}  // namespace candela
