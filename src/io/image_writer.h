// Image files by extension: .png (8-bit sRGB, tone-mapped), .exr and .pfm (linear float).
#pragma once

#include <string>

#include "camera/film.h"
#include "camera/tone_map.h"

namespace candela {

enum class ImageFormat { png, exr, pfm };

// False for an extension we cannot write.
bool image_format_for_path(const std::string& path, ImageFormat& format);
// Writes atomically; throws std::runtime_error on an I/O failure.
void write_image(const Film& film, const std::string& path, const DisplaySettings& display);

void write_png(const Film& film, const std::string& path, const DisplaySettings& display);
void write_exr(const Film& film, const std::string& path, double exposure);
void write_pfm(const Film& film, const std::string& path, double exposure);

}  // namespace candela
