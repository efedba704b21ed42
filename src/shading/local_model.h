// The local reflection model (000 eq. 2-7 and 5-2, 001's I_local; SPEC §7):
// I = ka·Ia + Σ_i Ip_i·f_at,i·s_i·[kd·(N·L_i) + ks·(R_i·V)^n]        (Phong)
//                                  [kd·(N·L_i) + ks·(N·H_i)^n]        (Blinn-Phong)
//                                  [kd·(N·L_i) + ks·(N·L_i)·k_s(λ)]   (Cook-Torrance, 000 §4.2.2)
// with a light contributing only where N·L > 0 (001's I_lum). In the Cook-Torrance form ks is
// the weight of the specular part (Cook and Torrance's s) and k_s(λ) = DGF/(π(N·V)(N·L)) the
// bidirectional specular reflectance of cook_torrance.h, colored through F.
#pragma once

#include "math/vector.h"
#include "shading/material.h"

namespace candela {

// The bracket for one light, times the light's arriving intensity. N is the shading normal
// on the viewer's side, V the unit vector toward the viewer, L toward the light.
Color direct_term(const Material& material, const SurfaceProperties& at, const Vec3& N, const Vec3& V,
                  const Vec3& L, const Color& light_intensity);

}  // namespace candela
