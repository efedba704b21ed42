#include "camera/orthographic_camera.h"

#include <cmath>
#include <stdexcept>

#include "camera/view_matrix.h"
#include "math/direction.h"

namespace candela {

OrthographicCamera::OrthographicCamera(const Vec3& eye, const Vec3& target, const Vec3& up, double left,
                                       double right, double bottom, double top, int width, int height,
                                       bool mirrored)
    : Camera(width, height), eye_(eye), left_(left), right_(right), bottom_(bottom), top_(top) {
  const Vec3 gaze = target - eye;
  const std::optional<Vec3> gaze_unit = direction_of(gaze);
  if (!gaze_unit) throw std::invalid_argument("target must differ from eye");
  gaze_ = *gaze_unit;
  const Vec3 x_axis = cross(gaze_, up);
  if (!(length(x_axis) > 1e-12 * length(up)))
    throw std::invalid_argument("up is parallel to the view direction");
  x_unit_ = normalize(x_axis);
  y_unit_ = cross(x_unit_, gaze_);
  if (mirrored) x_unit_ = -x_unit_;
  if (!(right > left) || !(top > bottom))
    throw std::invalid_argument("window must have right > left and top > bottom");
}

Eigen::Matrix4d OrthographicCamera::view_projection(double near, double far) const {
  const Eigen::Matrix4d view = view_matrix(x_unit_, y_unit_, gaze_, eye_);
  // u = l + (r − l)(ndc_x + 1)/2 and v = b + (t − b)(ndc_y + 1)/2, as generate_ray.
  Eigen::Matrix4d projection = Eigen::Matrix4d::Identity();
  projection(0, 0) = 2 / (right_ - left_);
  projection(0, 3) = -(right_ + left_) / (right_ - left_);
  projection(1, 1) = 2 / (top_ - bottom_);
  projection(1, 3) = -(top_ + bottom_) / (top_ - bottom_);
  projection(2, 2) = -2 / (far - near);
  projection(2, 3) = -(far + near) / (far - near);
  return projection * view;
}

Ray OrthographicCamera::generate_ray(double x, double y) const {
  const double u = left_ + (right_ - left_) * (x / width());
  const double v = bottom_ + (top_ - bottom_) * (1.0 - y / height());
  return Ray{eye_ + x_unit_ * u + y_unit_ * v, gaze_};
}

}  // namespace candela
