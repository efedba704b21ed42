// Pictures named on the command line (compare's A, B and --mask, convert's IN, falsecolor's IMAGE,
// report's --reference and --error-mask, render's --error-reference and --error-mask): read as
// linear RGB (validate/image_comparison.h read_linear_image), bad input as BadArgument.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "camera/film.h"
#include "validate/image_comparison.h"

namespace candela::cli {

// Throws BadArgument "LABEL: why" (LABEL the option and file as the message should name them).
LinearImage read_image_argument(const std::string& path, const std::string& label);

// Throws BadArgument "OPTION PATH is WxH, OF_WHAT WxH" unless the image is width × height.
void check_image_size(const Film& image, const std::string& option, const std::string& path, int width,
                      int height, const std::string& of_what);

// A mask image (white: the pixel counts) of width × height, as mask_from_image gives it.
std::vector<uint8_t> read_mask_argument(const std::string& path, const std::string& option, int width,
                                        int height, const std::string& of_what);

// A linear image as `candela render -o x.exr` writes it (film.exposure applied) back in the units
// the methods' films hold.
Film exposure_undone(const Film& image, double exposure);

}  // namespace candela::cli
