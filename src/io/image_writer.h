// Image files by extension: .png (8-bit sRGB, tone-mapped), .exr and .pfm (linear float), .hdr
// (Radiance RGBE: linear, 8-bit mantissas sharing an exponent, ~1 % steps, no negative values).
#pragma once

#include <string>

#include "camera/film.h"
#include "camera/tone_map.h"

namespace candela {

enum class ImageFormat { png, exr, pfm, hdr };

// The extensions write_image knows, for messages: ".png, .exr, .pfm or .hdr".
inline constexpr const char* kImageExtensions = ".png, .exr, .pfm or .hdr";

// False for an extension we cannot write.
bool image_format_for_path(const std::string& path, ImageFormat& format);
// What makes the image unwritable, or "": a pixel that is not finite (a light, emission
// or texture value so large that the arithmetic overflowed), or — for .exr and .pfm, which store
// single-precision floats (and .hdr, whose exponent reaches as far) — a pixel larger than the largest
// float once film.exposure is applied.
// The count and the first such pixel (x, y, value) are named.
std::string non_finite_image_problem(const Film& film, ImageFormat format, double exposure);

// Writes atomically; throws std::runtime_error on an I/O failure and with non_finite_image_problem's
// message for an image that problem refuses (callers that know the scene report it as bad input
// first).
void write_image(const Film& film, const std::string& path, const DisplaySettings& display);

void write_png(const Film& film, const std::string& path, const DisplaySettings& display);
void write_exr(const Film& film, const std::string& path, double exposure);
void write_pfm(const Film& film, const std::string& path, double exposure);
// Radiance's RGBE (stb_image_write, run-length encoded); negative values, which RGBE cannot hold
// (the negative lobes of the Mitchell and Lanczos filters), are written as 0.
void write_hdr(const Film& film, const std::string& path, double exposure);

}  // namespace candela
