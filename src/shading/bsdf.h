// Bidirectional scattering distribution functions for the path-traced reference (SPEC §12):
// Lambert, energy-conserving normalized Phong, microfacet (Beckmann and GGX, f = D·G·F /
// (4 (N·V)(N·L))), ideal mirror and smooth dielectric. A Bsdf is the sum of up to
// kMaxBsdfLobes lobes at one surface point, built from the classic material's parameters
// (shading/material_bsdf.h); it allocates nothing.
//
// Directions are world-space unit vectors pointing AWAY from the surface: wo toward the viewer
// (the previous vertex), wi toward where the light comes from. f is in physical units (a white
// Lambert surface has f = 1/π). Reflection lobes are two-sided (a surface seen from behind
// reflects like its front); the dielectric distinguishes outside (the side of the geometric
// normal) from inside.
#pragma once

#include <array>
#include <cstdint>

#include "math/vector.h"
#include "shading/fresnel.h"

namespace candela {

// An orthonormal frame about a unit normal: local (x, y, z) ↔ world x·s + y·t + z·n.
struct ShadingFrame {
  Vec3 s, t, n;
  static ShadingFrame from_normal(const Vec3& n);  // deterministic in n
  Vec3 to_local(const Vec3& v) const { return {dot(v, s), dot(v, t), dot(v, n)}; }
  Vec3 to_world(const Vec3& v) const { return s * v.x + t * v.y + n * v.z; }
};

// thin_dielectric: a thin sheet of the dielectric (a window pane, `"thin": true`): of what arrives
// it reflects thin_sheet(cos θ, ior, kt).reflectance and lets its transmittance through without
// bending it (shading/fresnel.h; kt is the sheet's transmissivity, one pass at normal incidence).
enum class LobeType : uint8_t { lambert, phong, microfacet, mirror, dielectric, thin_dielectric };
enum class MicrofacetDistribution : uint8_t { beckmann, ggx };

// One lobe's parameters (a plain value: Bsdf keeps them in a fixed array).
struct BsdfLobe {
  LobeType type = LobeType::lambert;
  Color weight;         // lambert: ρ; phong: ks; microfacet: ks (scales D·G·F/(4 cos cos));
                        // mirror: kr; dielectric: kt (scales both Fresnel parts);
                        // thin_dielectric: kt, the transmissivity of one pass
  double exponent = 1;  // phong: n of cos^n α, α the angle between wi and the mirror of wo
  double alpha = 0.3;   // microfacet roughness (Beckmann: rms slope m)
  MicrofacetDistribution distribution = MicrofacetDistribution::beckmann;
  Fresnel fresnel;  // microfacet: F per channel (dielectric, conductor or Schlick); lambert
                    // beneath_facets: the facets' F above it
  // lambert: the diffuse lies beneath microfacets of Fresnel factor `fresnel` (glTF's
  // metallic-roughness BRDF): f = ρ (1 − F(wo·h)) / π, h the half vector of wo and wi.
  bool beneath_facets = false;
  double ior = 1.5;  // dielectric, thin_dielectric: index inside relative to outside
};

struct BsdfSample {
  Vec3 wi;             // world, unit
  Color weight;        // f·|cos θ_i|/pdf, already divided by the probability of the chosen lobe;
                       // for a delta lobe the fraction of radiance carried over
  double pdf = 0;      // solid-angle density of wi under sample() (all non-delta lobes mixed); 0 when delta
  bool delta = false;  // from a mirror or dielectric lobe: no MIS, evaluate() does not see it
  bool transmission = false;
  // Through a thin sheet: wi = −wo, the ray goes on as if the sheet were not there, save `weight`.
  // A path tracer takes it as no vertex (its shadow rays cross such sheets too, integrators/
  // path_tracer.cpp), so what lies beyond is weighed against the vertex before the sheet.
  bool passthrough = false;
  double eta = 1;  // n_t/n_i when the sample crossed the surface, else 1 (Russian roulette's η²)
};

inline constexpr int kMaxBsdfLobes = 4;

class Bsdf {
 public:
  // shading: the frame of the (bumped, interpolated) shading normal, oriented to the geometric
  // normal's side; geometric_normal: unit, the outside of the surface. sides_by_shading_normal:
  // the reflection lobes connect any wo, wi above the shading normal's plane, also where wi dips
  // under the flat facet — for a smooth mesh whose rays leave from Hanika's lifted point
  // (SurfaceHit::lifted_toward), where the shadow ray, not the facet, decides what is lit.
  Bsdf(const ShadingFrame& shading, const Vec3& geometric_normal, bool sides_by_shading_normal = false)
      : frame_(shading), geometric_(geometric_normal), sides_by_shading_normal_(sides_by_shading_normal) {}
  // Adds a lobe; lobes beyond kMaxBsdfLobes or with a black weight are dropped.
  void add(const BsdfLobe& lobe);
  int lobe_count() const { return count_; }
  const ShadingFrame& frame() const { return frame_; }
  const Vec3& geometric_normal() const { return geometric_; }
  const BsdfLobe& lobe(int index) const { return lobes_[index]; }
  // Scales every lobe's weight per channel so that no channel's total reflectance can exceed 1
  // (energy conservation when a material's kd + ks + kr + kt add up to more than 1).
  void conserve_energy();

  // Sum of the non-delta lobes' f(wo, wi); zero for wo, wi on opposite sides of the geometric
  // normal (no light leaks through bumped normals) unless sides_by_shading_normal.
  Color evaluate(const Vec3& wo, const Vec3& wi) const;
  // The density sample() draws wi with, restricted to its non-delta part (the probability of
  // choosing each non-delta lobe times its pdf).
  double pdf(const Vec3& wo, const Vec3& wi) const;
  // Picks a lobe with probability proportional to its weight's average (u_lobe), then a
  // direction from it (u). False when nothing is sampled (weight zero).
  bool sample(const Vec3& wo, double u_lobe, const Vec2& u, BsdfSample& sample) const;
  // Whether any lobe is not a delta (next-event estimation is worth doing).
  bool has_non_delta() const;

 private:
  ShadingFrame frame_;
  Vec3 geometric_;
  bool sides_by_shading_normal_ = false;
  std::array<BsdfLobe, kMaxBsdfLobes> lobes_{};
  int count_ = 0;
};

}  // namespace candela
