// Cameras map a point of the image to a primary ray (SPEC §6).
#pragma once

#include <Eigen/Dense>
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

  // World to clip coordinates (OpenGL conventions: x, y, z in [−w, w] inside the view volume,
  // z = −w at the near plane, w > 0 in front of the eye) such that a point seen at image
  // position (x, y) — the generate_ray convention — lands at ndc x = 2x/width − 1,
  // ndc y = 1 − 2y/height. near and far bound the depth range (0 < near < far).
  virtual Eigen::Matrix4d view_projection(double near, double far) const = 0;
  // Where the eye is (perspective) or a point of the view plane (orthographic), and the unit
  // direction of view: the raster method uses them to choose near and far.
  virtual Vec3 eye_position() const = 0;
  virtual Vec3 view_direction() const = 0;

  int width() const { return width_; }
  int height() const { return height_; }

 private:
  int width_;
  int height_;
};

}  // namespace candela
