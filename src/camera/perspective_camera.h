#pragma once

#include "camera/camera.h"

namespace candela {

// 000 §5.2: eye E, gaze G toward the target, up U, horizontal field of view 2θ; the vertical
// one follows from the resolution (square pixels). X = G×U, Y = X×G, H = d tanθ X,
// V = d tanφ Y, S = E + dG + (2x'−1)H + (2y'−1)V with x' = (i+0.5)/Rx, y' = (j+0.5)/Ry and
// (x', y') measured from the lower-left corner of the view plane. `mirrored` turns X the other
// way (X = U × G): a left-handed camera, whose image is the right-handed one mirrored left to right
// (pbrt's camera space, io/pbrt_scene.h).
class PerspectiveCamera final : public Camera {
 public:
  PerspectiveCamera(const Vec3& eye, const Vec3& target, const Vec3& up, double horizontal_fov_degrees,
                    int width, int height, bool mirrored = false);
  Ray generate_ray(double x, double y) const override;
  std::string_view type_name() const override { return "perspective"; }
  // The OpenGL frustum whose pixel centres are generate_ray's: 1/tanθ across, 1/tanφ up.
  Eigen::Matrix4d view_projection(double near, double far) const override;
  Vec3 eye_position() const override { return eye_; }
  Vec3 view_direction() const override { return gaze_; }

  const Vec3& gaze() const { return gaze_; }
  const Vec3& half_width() const { return half_width_; }    // H (d = 1)
  const Vec3& half_height() const { return half_height_; }  // V (d = 1)

 private:
  Vec3 eye_, gaze_, half_width_, half_height_;
};

}  // namespace candela
