#include "raster/hemicube_views.h"

#include <cmath>
#include <stdexcept>

#include "camera/view_matrix.h"

namespace candela {

HemicubeFaceAxes hemicube_face_axes(const Vec3& normal, const Vec3& tangent_hint, HemicubeFace face) {
  const double normal_length = length(normal);
  if (!(normal_length > 0) || !std::isfinite(normal_length))
    throw std::invalid_argument("hemicube: the normal must be finite and non-zero");
  const Vec3 n = normal / normal_length;
  // Gram–Schmidt on the hint; a hint along n (or unusable) gives way to any perpendicular.
  Vec3 t = tangent_hint - n * dot(tangent_hint, n);
  const double t_length = length(t);
  if (t_length > 1e-9 * length(tangent_hint) && std::isfinite(t_length)) {
    t = t / t_length;
  } else {
    Vec3 unused;
    orthonormal_basis(n, t, unused);
  }
  const Vec3 b = cross(n, t);
  switch (face) {
    case HemicubeFace::top:
      return {n, b, t};
    case HemicubeFace::front:
      return {t, -b, n};
    case HemicubeFace::back:
      return {-t, b, n};
    case HemicubeFace::right:
      return {b, t, n};
    case HemicubeFace::left:
      return {-b, -t, n};
  }
  throw std::invalid_argument("hemicube: unknown face");
}

Eigen::Matrix4d hemicube_view_projection(const Vec3& center, const Vec3& normal, const Vec3& tangent_hint,
                                         HemicubeFace face, double near, double far) {
  if (!(near > 0 && near < far && std::isfinite(far)))
    throw std::invalid_argument("hemicube: near and far must satisfy 0 < near < far");
  if (!is_finite(center)) throw std::invalid_argument("hemicube: the centre must be finite");
  const HemicubeFaceAxes axes = hemicube_face_axes(normal, tangent_hint, face);
  // View space as PerspectiveCamera::view_projection builds it: x along right, y along up,
  // looking down −z; then the OpenGL frustum with tan 45° = 1 across and up.
  const Eigen::Matrix4d view = view_matrix(axes.right, axes.up, axes.forward, center);
  Eigen::Matrix4d projection = Eigen::Matrix4d::Zero();
  projection(0, 0) = 1;
  projection(1, 1) = 1;
  projection(2, 2) = -(far + near) / (far - near);
  projection(2, 3) = -2 * far * near / (far - near);
  projection(3, 2) = -1;
  return projection * view;
}

}  // namespace candela
