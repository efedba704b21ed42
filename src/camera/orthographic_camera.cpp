#include "camera/orthographic_camera.h"

#include <stdexcept>

namespace candela {

OrthographicCamera::OrthographicCamera(const Vec3& eye, const Vec3& target, const Vec3& up,
                                       double left, double right, double bottom, double top,
                                       int width, int height)
    : Camera(width, height), eye_(eye), left_(left), right_(right), bottom_(bottom), top_(top) {
  const Vec3 gaze = target - eye;
  if (!(length(gaze) > 0)) throw std::invalid_argument("target must differ from eye");
  gaze_ = normalize(gaze);
  const Vec3 x_axis = cross(gaze_, up);
  if (!(length(x_axis) > 1e-12 * length(up))) throw std::invalid_argument("up is parallel to the view direction");
  x_unit_ = normalize(x_axis);
  y_unit_ = cross(x_unit_, gaze_);
  if (!(right > left) || !(top > bottom)) throw std::invalid_argument("window must have right > left and top > bottom");
}

Ray OrthographicCamera::generate_ray(double x, double y) const {
  const double u = left_ + (right_ - left_) * (x / width());
  const double v = bottom_ + (top_ - bottom_) * (1.0 - y / height());
  return Ray{eye_ + x_unit_ * u + y_unit_ * v, gaze_};
}

}  // namespace candela
