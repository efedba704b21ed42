// The local reflection model (000 eq. 2-7 and 5-2, 001's I_local; SPEC §7):
// I = ka·Ia + Σ_i Ip_i·f_at,i·s_i·[kd·(N·L_i) + ks·(R_i·V)^n]   (Phong)
//                                  [kd·(N·L_i) + ks·(N·H_i)^n]   (Blinn-Phong)
// with a light contributing only where N·L > 0 (001's I_lum).
#pragma once

#include "math/vector.h"
#include "shading/material.h"

namespace candela {

// The diffuse + specular bracket for one light, times the light's arriving intensity.
// N is the shading normal on the viewer's side, V the unit vector toward the viewer,
// L toward the light, kd the diffuse colour at the point.
Color direct_term(const Material& material, const Color& kd, const Vec3& N, const Vec3& V,
                  const Vec3& L, const Color& light_intensity);

}  // namespace candela
