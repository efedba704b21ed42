#include "camera/perspective_camera.h"

#include <cmath>
#include <stdexcept>

#include "camera/view_matrix.h"
#include "math/constants.h"
#include "math/direction.h"

namespace candela {

PerspectiveCamera::PerspectiveCamera(const Vec3& eye, const Vec3& target, const Vec3& up,
                                     double horizontal_fov_degrees, int width, int height, bool mirrored)
    : Camera(width, height), eye_(eye) {
  const Vec3 gaze = target - eye;
  const std::optional<Vec3> gaze_unit = direction_of(gaze);
  if (!gaze_unit) throw std::invalid_argument("target must differ from eye");
  gaze_ = *gaze_unit;
  const Vec3 x_axis = cross(gaze_, up);  // X = G × U
  if (!(length(x_axis) > 1e-12 * length(up)))
    throw std::invalid_argument("up is parallel to the view direction");
  const Vec3 x_unit = normalize(x_axis);
  const Vec3 y_unit = cross(x_unit, gaze_);  // Y = X × G, the same either way
  const double tan_theta = std::tan(degrees_to_radians(horizontal_fov_degrees) / 2);
  const double tan_phi = tan_theta * height / width;
  half_width_ = x_unit * (mirrored ? -tan_theta : tan_theta);
  half_height_ = y_unit * tan_phi;
}

Eigen::Matrix4d PerspectiveCamera::view_projection(double near, double far) const {
  // View space: x along X, y along Y, looking down −z (z = −G·(p − E)).
  const Eigen::Matrix4d view = view_matrix(normalize(half_width_), normalize(half_height_), gaze_, eye_);
  // ndc x = (x_v / −z_v)/tanθ and ndc y = (y_v / −z_v)/tanφ: generate_ray's direction
  // G + (2x'−1)H + (2y'−1)V read backwards.
  Eigen::Matrix4d projection = Eigen::Matrix4d::Zero();
  projection(0, 0) = 1 / length(half_width_);
  projection(1, 1) = 1 / length(half_height_);
  projection(2, 2) = -(far + near) / (far - near);
  projection(2, 3) = -2 * far * near / (far - near);
  projection(3, 2) = -1;
  return projection * view;
}

Ray PerspectiveCamera::generate_ray(double x, double y) const {
  const double x_view = x / width();
  const double y_view = 1.0 - y / height();  // image rows run downward, the view plane's y up
  const Vec3 direction = gaze_ + half_width_ * (2 * x_view - 1) + half_height_ * (2 * y_view - 1);
  return Ray{eye_, normalize(direction)};
}

}  // namespace candela
