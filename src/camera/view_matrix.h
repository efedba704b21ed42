// The world-to-view matrix shared by the cameras and the hemicube faces: view x along `right`,
// y along `up`, looking down −z along `forward` (OpenGL's eye space), the eye at the origin.
#pragma once

#include <Eigen/Dense>

#include "math/vector.h"

namespace candela {

inline Eigen::Matrix4d view_matrix(const Vec3& right, const Vec3& up, const Vec3& forward, const Vec3& eye) {
  Eigen::Matrix4d view = Eigen::Matrix4d::Identity();
  const Vec3 rows[3] = {right, up, -forward};
  for (int r = 0; r < 3; ++r) {
    view(r, 0) = rows[r].x;
    view(r, 1) = rows[r].y;
    view(r, 2) = rows[r].z;
    view(r, 3) = -dot(rows[r], eye);
  }
  return view;
}

}  // namespace candela
