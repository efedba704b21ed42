#pragma once

#include "camera/camera.h"

namespace candela {

// 001: rays perpendicular to the image window (l, r, b, t) in the view plane through the
// eye: u = l + (r − l)(i + 0.5)/Nx, v = b + (t − b)(j + 0.5)/Ny, direction G. `mirrored` turns
// the view plane's x axis the other way (U × G instead of G × U), as PerspectiveCamera's.
class OrthographicCamera final : public Camera {
 public:
  OrthographicCamera(const Vec3& eye, const Vec3& target, const Vec3& up, double left, double right,
                     double bottom, double top, int width, int height, bool mirrored = false);
  Ray generate_ray(double x, double y) const override;
  std::string_view type_name() const override { return "orthographic"; }
  // The window (l, r, b, t) onto ndc [−1, 1]²; depth from the eye plane along the gaze.
  Eigen::Matrix4d view_projection(double near, double far) const override;
  Vec3 eye_position() const override { return eye_; }
  Vec3 view_direction() const override { return gaze_; }

 private:
  Vec3 eye_, gaze_, x_unit_, y_unit_;
  double left_, right_, bottom_, top_;
};

}  // namespace candela
