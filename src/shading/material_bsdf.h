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
// lobe's weight in that channel shrinks in proportion. A layered material (Material::layered, glTF's
// metallic-roughness BRDF) keeps its microfacet lobe out of that sum, and its lambert lobe lies
// beneath the facets: ρ (1 − F(wo·h)) / π, the light the facet h between wo and wi does not
// reflect (BsdfLobe::beneath_facets).
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

// What a thin sheet (Material::thin with kt: a window pane) lets through where a ray crosses it along
// `direction`: its transmittance T(θ) (shading/fresnel.h) at the angle to its bumped shading
// normal, with the weight its BSDF's thin_dielectric lobe has — what that lobe's passthrough samples
// carry on average, so that a shadow ray through the pane and a path continued through it estimate
// the same light. Black for any other material.
Color thin_sheet_transmittance(const Material& material, const SurfaceHit& hit, const Vec3& direction);

}  // namespace candela
