#include "image_arguments.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <exception>

#include "commands.h"

namespace candela::cli {

LinearImage read_image_argument(const std::string& path, const std::string& label) {
  try {
    return read_linear_image(path);
  } catch (const std::exception& e) {
    throw BadArgument(fmt::format("{}: {}", label, e.what()));
  }
}

void check_image_size(const Film& image, const std::string& option, const std::string& path, int width,
                      int height, const std::string& of_what) {
  if (image.width() != width || image.height() != height)
    throw BadArgument(fmt::format("{} {} is {}x{}, {} {}x{}", option, path, image.width(), image.height(),
                                  of_what, width, height));
}

std::vector<uint8_t> read_mask_argument(const std::string& path, const std::string& option, int width,
                                        int height, const std::string& of_what) {
  const LinearImage mask = read_image_argument(path, option);
  check_image_size(mask.film, option, path, width, height, of_what);
  std::vector<uint8_t> included = mask_from_image(mask.film);
  // A mask that leaves out every pixel measures nothing; refused before any work (an
  // all-black --error-mask once ran the whole render, wrote the image, then failed).
  if (std::find(included.begin(), included.end(), uint8_t(1)) == included.end())
    throw BadArgument(fmt::format("{} {} excludes every pixel (none has luminance above {})", option, path,
                                  kMaskThreshold));
  return included;
}

Film exposure_undone(const Film& image, double exposure) {
  const double undo = std::exp2(-exposure);
  Film film(image.width(), image.height());
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) film.at(x, y) = image.at(x, y) * undo;
  return film;
}

}  // namespace candela::cli
