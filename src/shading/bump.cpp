#include "shading/bump.h"

#include <cmath>

namespace candela {

namespace {

// The hit moved by `step` along one parameter: uv, world and object positions together, so
// 2D (uv) and solid (object position) height textures both see the displacement.
SurfaceHit moved(const SurfaceHit& hit, int parameter, double step) {
  SurfaceHit shifted = hit;
  if (parameter == 0) {
    shifted.uv.x += step;
    shifted.position += hit.dpdu * step;
    shifted.object_position += hit.object_dpdu() * step;
  } else {
    shifted.uv.y += step;
    shifted.position += hit.dpdv * step;
    shifted.object_position += hit.object_dpdv() * step;
  }
  return shifted;
}

}  // namespace

Vec3 bumped_normal(const BumpMap& bump, const SurfaceHit& hit) {
  const Vec3& n = hit.shading_normal;
  if (!bump.height) return n;
  const double delta = bump.delta;
  const auto slope = [&](int parameter) {
    const double ahead = bump.height->evaluate_scalar(moved(hit, parameter, delta));
    const double behind = bump.height->evaluate_scalar(moved(hit, parameter, -delta));
    return bump.scale * (ahead - behind) / (2 * delta);
  };
  const Vec3 unbumped = cross(hit.dpdu, hit.dpdv);
  const double unbumped_length = length(unbumped);
  if (!(unbumped_length > 0)) return n;  // a pole: no tangent plane to tilt
  const double f_u = slope(0);
  const double f_v = slope(1);
  // (dpdu + f_u·n) × (dpdv + f_v·n) = dpdu×dpdv + f_u·(n×dpdv) + f_v·(dpdu×n). The first term
  // is taken as n·|dpdu×dpdv| (oriented as dpdu×dpdv): the same on analytic shapes, where n is
  // along dpdu×dpdv, and it keeps a smooth mesh's interpolated normal instead of its face's.
  const double side = dot(unbumped, n) < 0 ? -1.0 : 1.0;
  const Vec3 normal = n * (side * unbumped_length) + cross(n, hit.dpdv) * f_u + cross(hit.dpdu, n) * f_v;
  const double normal_length = length(normal);
  if (!(normal_length > 0) || !std::isfinite(normal_length)) return n;
  // Keep the shading normal's side.
  return normal * (side / normal_length);
}

}  // namespace candela
