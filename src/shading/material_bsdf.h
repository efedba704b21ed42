// The classic material (shading/material.h) as a sum of BSDF lobes for the path tracer
// (SPEC §12; docs/materials.md, "Path tracing"):
//   kd                              → lambert, ρ = kd clamped to [0, 1] (SurfaceProperties::diffuse_albedo)
//   ks > 0, phong or blinn-phong    → normalized Phong, weight ks, exponent n (shininess)
//   ks > 0, cook-torrance           → microfacet, weight ks, α = roughness, Material::microfacet
//                                     (Beckmann or GGX), Fresnel per channel: Material::fresnel
//   kr > 0                          → mirror, weight kr
//   kt > 0                          → smooth dielectric, weight kt, index ior (a thin sheet's
//                                     lobe when the material is thin)
// and finally Bsdf::conserve_energy(): where kd + ks + kr + kt exceeds 1 in a channel, every
// lobe's weight in that channel shrinks in proportion.
#pragma once

#include "geometry/surface_hit.h"
#include "math/vector.h"
#include "shading/bsdf.h"
#include "shading/material.h"

namespace candela {

// at: the material's parameters at the hit (Material::at); shading_normal: the unit
// (bumped, interpolated) shading normal, turned here to the geometric normal's side.
Bsdf make_bsdf(const Material& material, const SurfaceProperties& at, const SurfaceHit& hit,
               const Vec3& shading_normal);

}  // namespace candela
