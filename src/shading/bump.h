// Bump mapping (000 §4.2.1; Blinn 1978): the surface is shaded as if displaced to
// q' = q + f(q)·n, while the geometry (and so the silhouette) stays as it is. With
// f = scale·height(u, v) the displaced surface has the tangents
//   ∂q'/∂u = dpdu + f_u·n (+ f·∂n/∂u, dropped as Blinn does: f is small),   likewise for v,
// and its normal is their cross product, turned to the side of the original normal, with
// dpdu × dpdv replaced by n·|dpdu × dpdv| so a smooth mesh keeps its interpolated normal. f_u and f_v
// are central differences of the height texture, the hit moved by ±delta in u (and in
// position and object position along dpdu), so any texture (image, waves, noise) can be a
// height field.
#pragma once

#include "geometry/surface_hit.h"
#include "shading/material.h"

namespace candela {

// The perturbed unit shading normal; the hit's own shading normal where the bump has no
// height texture or the tangents are degenerate (the poles of a sphere).
Vec3 bumped_normal(const BumpMap& bump, const SurfaceHit& hit);

}  // namespace candela
