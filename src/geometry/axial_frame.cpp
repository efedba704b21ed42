#include "geometry/axial_frame.h"

#include <cmath>
#include <stdexcept>

#include "geometry/shape.h"
#include "math/constants.h"
#include "sampling/warps.h"

namespace candela {

AxialFrame::AxialFrame(const Vec3& base, const Vec3& cap) : base_(base) {
  if (!is_finite(base) || !is_finite(cap)) throw std::invalid_argument("end points must be finite");
  height_ = length(cap - base);
  if (!(height_ > 0) || !std::isfinite(height_)) throw std::invalid_argument("base and cap must differ");
  axis_ = (cap - base) / height_;
  orthonormal_basis(axis_, x_axis_, y_axis_);
}

bool AxialFrame::cap_distance(const Vec3& origin, const Vec3& direction, double z, double radius, double& t) {
  if (direction.z == 0) return false;
  t = (z - origin.z) / direction.z;
  const double x = origin.x + direction.x * t, y = origin.y + direction.y * t;
  return x * x + y * y <= radius * radius;
}

AxialFrame::Around AxialFrame::around(const Vec3& point) const {
  Around result;
  result.local = to_local(point - base_);
  result.r = std::sqrt(result.local.x * result.local.x + result.local.y * result.local.y);
  result.phi = std::atan2(result.local.y, result.local.x);
  if (result.phi < 0) result.phi += 2 * kPi;
  const double cos_phi = std::cos(result.phi), sin_phi = std::sin(result.phi);
  result.radial = x_axis_ * cos_phi + y_axis_ * sin_phi;
  result.tangent = y_axis_ * cos_phi - x_axis_ * sin_phi;
  return result;
}

void AxialFrame::sample_end_disc(const Vec3& centre, bool cap, double radius, const Vec2& u,
                                 SurfaceSample& sample) const {
  const Vec2 d = square_to_uniform_disc_concentric(u);
  sample.position = centre + (x_axis_ * d.x + y_axis_ * d.y) * radius;
  sample.normal = cap ? axis_ : -axis_;
}

}  // namespace candela
