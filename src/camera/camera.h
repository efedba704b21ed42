// Cameras map a point of the image to a primary ray (SPEC §6).
#pragma once

#include <string_view>

#include "math/ray.h"

namespace candela {

class Camera {
 public:
  Camera(int width, int height) : width_(width), height_(height) {}
  virtual ~Camera() = default;

  // (x, y) in image coordinates: (0, 0) is the top-left corner of the image and pixel (i, j)
  // covers [i, i+1) × [j, j+1), so its centre is (i + 0.5, j + 0.5).
  virtual Ray generate_ray(double x, double y) const = 0;
  virtual std::string_view type_name() const = 0;

  int width() const { return width_; }
  int height() const { return height_; }

 private:
  int width_;
  int height_;
};

}  // namespace candela
