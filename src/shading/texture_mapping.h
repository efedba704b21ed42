// From a surface hit to texture coordinates (u, v) (000 §4.1; SPEC §7). Every mapping then
// applies `scale` and `offset`: (u, v) := (u·scale_u + offset_u, v·scale_v + offset_v).
#pragma once

#include <memory>
#include <string_view>

#include "geometry/surface_hit.h"
#include "math/transform.h"
#include "math/vector.h"

namespace candela {

struct UvTransform {
  Vec2 scale{1, 1};
  Vec2 offset{0, 0};
  Vec2 apply(const Vec2& uv) const { return {uv.x * scale.x + offset.x, uv.y * scale.y + offset.y}; }
};

class TextureMapping {
 public:
  explicit TextureMapping(const UvTransform& uv_transform = {}) : uv_transform_(uv_transform) {}
  virtual ~TextureMapping() = default;
  Vec2 map(const SurfaceHit& hit) const { return uv_transform_.apply(raw(hit)); }
  // The mapping's own coordinates, before scale and offset.
  virtual Vec2 raw(const SurfaceHit& hit) const = 0;
  virtual std::string_view type_name() const = 0;

 private:
  UvTransform uv_transform_;
};

// The shape's own parametric uv (000 §4.1.2): quad/polygon, disc, cylinder, cone, torus, box
// faces, sphere (pbrt's φ/2π, θ/π), and the OBJ file's vt for meshes.
class ParametricMapping final : public TextureMapping {
 public:
  using TextureMapping::TextureMapping;
  Vec2 raw(const SurfaceHit& hit) const override { return hit.uv; }
  std::string_view type_name() const override { return "uv"; }
};

// 000 §4.1.1, eqs. 4-2..4-5: latitude and longitude of the unit vector N from `center` to the
// point, or of the geometric normal when no centre is given (both in object coordinates, so
// the texture turns with the object's transform).
// v = φ/π with φ = acos(−Tp·N) (0 at the south pole, 1 at the north pole);
// u = acos((Te·N)/sin φ)/(2π), u := 1 − u when (Tp×Te)·N < 0; u = 0 at the poles.
class SphericalMapping final : public TextureMapping {
 public:
  // pole (Tp) and equator (Te) are made orthonormal (Te loses its component along Tp).
  SphericalMapping(const Vec3& pole, const Vec3& equator, const Vec3* center, const UvTransform& uv = {});
  Vec2 raw(const SurfaceHit& hit) const override;
  Vec2 of_direction(const Vec3& unit_n) const;
  std::string_view type_name() const override { return "spherical"; }
  // Without a centre the mapping reads only the normal, which a bump map's finite differences
  // do not move: such a mapping cannot carry bump heights.
  bool has_center() const { return has_center_; }

 private:
  Vec3 pole_, equator_, east_;  // east = Tp × Te
  bool has_center_ = false;
  Vec3 center_;
};

// Projection onto a plane: u = (p − origin)·u_axis, v = (p − origin)·v_axis, p in object
// coordinates (a texture of period 1 repeats every |u_axis|⁻¹ units).
class PlanarMapping final : public TextureMapping {
 public:
  PlanarMapping(const Vec3& origin, const Vec3& u_axis, const Vec3& v_axis, const UvTransform& uv = {});
  Vec2 raw(const SurfaceHit& hit) const override;
  std::string_view type_name() const override { return "planar"; }

 private:
  Vec3 origin_, u_axis_, v_axis_;
};

// Cylindrical projection about an axis through `center`: u = angle about the axis from
// `reference` / 2π in [0, 1), v = height along the axis / `height`.
class CylindricalMapping final : public TextureMapping {
 public:
  CylindricalMapping(const Vec3& center, const Vec3& axis, const Vec3& reference, double height,
                     const UvTransform& uv = {});
  Vec2 raw(const SurfaceHit& hit) const override;
  std::string_view type_name() const override { return "cylindrical"; }

 private:
  Vec3 center_, axis_, reference_, side_;
  double height_;
};

}  // namespace candela
