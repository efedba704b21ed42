// The local part shared by the local and whitted methods: ambient plus every light that
// reaches the point, with transparent shadows (SPEC §8, 001's s ∈ [0, 1]).
#pragma once

#include "integrators/ray_tracing_method.h"

namespace candela {

// How much of a light's intensity arrives along the segment from origin toward L over
// distance: 1 when nothing is in the way, 0 behind an opaque object, and for transparent
// occluders the product of their kt (once per object crossed), of the see-through
// transparency t of every surface crossed (000 §4.4, n_z = |N·L|) and exp(−absorption·length
// inside) — the glass globe's shadow of 000 §5.9, darker where the path through the glass
// is longer.
Color shadow_transmittance(const Scene& scene, const Vec3& origin, const Vec3& L, double distance,
                           TraceContext& context, int tree_parent);

// ka·Ia + Σ Ip·f_at·s·[kd(N·L) + ks(...)^n] at the hit seen from direction V (unit, toward
// the viewer). Shadow rays leave from the hit offset along the geometric normal.
// `at` holds the material's parameters at the hit, its shading normal already bumped.
Color local_illumination(const Scene& scene, const Intersection& hit, const SurfaceProperties& at,
                         const Vec3& V, bool shadows, TraceContext& context, int tree_parent);

}  // namespace candela
