// Linear float RGB pixels (SPEC §6: the film keeps linear float RGB).
#pragma once

#include <vector>

#include "math/vector.h"

namespace candela {

class Film {
 public:
  Film(int width, int height) : width_(width), height_(height), pixels_(std::size_t(width) * height) {}
  int width() const { return width_; }
  int height() const { return height_; }
  Color& at(int x, int y) { return pixels_[std::size_t(y) * width_ + x]; }
  const Color& at(int x, int y) const { return pixels_[std::size_t(y) * width_ + x]; }
  const std::vector<Color>& pixels() const { return pixels_; }

 private:
  int width_, height_;
  std::vector<Color> pixels_;
};

}  // namespace candela
