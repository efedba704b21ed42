#include "shading/texture_mapping.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "math/constants.h"

namespace candela {

namespace {

Vec3 unit_or_throw(const Vec3& v, const char* what) {
  const double l = length(v);
  if (!(l > 0) || !std::isfinite(l))
    throw std::invalid_argument(std::string(what) + " must be a non-zero vector");
  return v / l;
}

// The part of v orthogonal to the unit vector axis, normalised.
Vec3 orthogonal_unit(const Vec3& v, const Vec3& axis, const char* what) {
  const Vec3 w = v - axis * dot(v, axis);
  const double l = length(w);
  if (!(l > 1e-9 * length(v)))
    throw std::invalid_argument(std::string(what) + " must not be parallel to the axis");
  return w / l;
}

}  // namespace

SphericalMapping::SphericalMapping(const Vec3& pole, const Vec3& equator, const Vec3* center,
                                   const UvTransform& uv)
    : TextureMapping(uv) {
  pole_ = unit_or_throw(pole, "pole");
  equator_ = orthogonal_unit(equator, pole_, "equator");
  east_ = cross(pole_, equator_);
  if (center) {
    has_center_ = true;
    center_ = *center;
  }
}

Vec2 SphericalMapping::of_direction(const Vec3& N) const {
  // 000 eq. 4-3: latitude from the south pole.
  const double phi = std::acos(std::clamp(-dot(pole_, N), -1.0, 1.0));
  const double v = phi / kPi;  // eq. 4-2
  const double sin_phi = std::sin(phi);
  if (!(sin_phi > 1e-12)) return {0, v};  // at the poles u = 0
  // eq. 4-4; the clamp keeps rounding from leaving acos's domain near Te.
  double u = std::acos(std::clamp(dot(equator_, N) / sin_phi, -1.0, 1.0)) / (2 * kPi);
  // eq. 4-5: the far side of Te takes the other half of the equator.
  if (dot(east_, N) < 0) u = 1 - u;
  return {u, v};
}

Vec2 SphericalMapping::raw(const SurfaceHit& hit) const {
  if (!has_center_) return of_direction(hit.object_normal());
  const Vec3 d = hit.object_position - center_;
  const double l = length(d);
  if (!(l > 0)) return {0, 0.5};
  return of_direction(d / l);
}

PlanarMapping::PlanarMapping(const Vec3& origin, const Vec3& u_axis, const Vec3& v_axis,
                             const UvTransform& uv)
    : TextureMapping(uv), origin_(origin), u_axis_(u_axis), v_axis_(v_axis) {
  if (!(length(cross(u_axis, v_axis)) > 0))
    throw std::invalid_argument("u_axis and v_axis must be non-zero and not parallel");
}

Vec2 PlanarMapping::raw(const SurfaceHit& hit) const {
  const Vec3 d = hit.object_position - origin_;
  return {dot(d, u_axis_), dot(d, v_axis_)};
}

CylindricalMapping::CylindricalMapping(const Vec3& center, const Vec3& axis, const Vec3& reference,
                                       double height, const UvTransform& uv)
    : TextureMapping(uv), center_(center), height_(height) {
  if (!(height > 0)) throw std::invalid_argument("height must be > 0");
  axis_ = unit_or_throw(axis, "axis");
  reference_ = orthogonal_unit(reference, axis_, "reference");
  side_ = cross(axis_, reference_);
}

Vec2 CylindricalMapping::raw(const SurfaceHit& hit) const {
  const Vec3 d = hit.object_position - center_;
  double angle = std::atan2(dot(d, side_), dot(d, reference_));
  if (angle < 0) angle += 2 * kPi;
  double u = angle / (2 * kPi);
  if (u >= 1) u = 0;
  return {u, dot(d, axis_) / height_};
}

}  // namespace candela
