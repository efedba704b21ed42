// The classic material of the local model and Whitted ray tracing (SPEC §7, §8; 000 §2–§4).
// Every parameter is a texture (a constant one unless the scene gives a texture), evaluated
// once per hit into SurfaceProperties.
#pragma once

#include <algorithm>
#include <memory>
#include <string>

#include "shading/bsdf.h"
#include "shading/texture.h"

namespace candela {

enum class SpecularModel { phong, blinn_phong, cook_torrance };

// The see-through blend of 000 §4.4 (besides refraction): I = (1 − t)·I_surface + t·I_behind,
// where t is the transparency (0 opaque, 1 clear) and n_z = |N·V| the cosine between the
// normal and the direction to the viewer (the seed's n_z in eye coordinates):
//   constant   t
//   linear     t = t_min + (t_max − t_min)·n_z
//   nonlinear  t = t_min + (t_max − t_min)·(1 − (1 − n_z)^m)
// so a glass vase is least transparent (t_min) at its silhouette, where light crosses the
// most material (000 Figure 29).
enum class TransparencyModel { none, constant, linear, nonlinear };

struct Transparency {
  TransparencyModel model = TransparencyModel::none;
  double t_min = 0;  // also the constant model's t
  double t_max = 0;
  double exponent = 2;  // m of the nonlinear model, "of the order of 2 or 3"
  bool active() const { return model != TransparencyModel::none; }
  double at(double n_z) const;
};

// 000 §4.2.1: the surface is shaded as if displaced to q' = q + f(q)·n, f = scale·height.
struct BumpMap {
  std::shared_ptr<const Texture> height;  // null: no bump mapping
  double scale = 1;
  double delta = 1e-4;  // finite-difference step in (u, v)
};

// The parameters at one surface point.
struct SurfaceProperties {
  Color ka, kd;
  double ks = 0, shininess = 1, kr = 0, kt = 0, ior = 1, roughness = 0.3;

  // kd clamped to [0, 1] per channel: the diffuse reflectance ρ (the albedo β) of the radiosity
  // methods, which must not reflect more than arrives.
  Color diffuse_albedo() const {
    Color albedo;
    for (int c = 0; c < 3; ++c) albedo[c] = std::clamp(kd[c], 0.0, 1.0);
    return albedo;
  }
};

struct Material {
  std::string name;
  std::shared_ptr<const Texture> kd;         // diffuse reflectance per channel (000 §2.9)
  std::shared_ptr<const Texture> ka;         // ambient reflectance; null: ka = kd (000 eq. 5-2: kd·Ia)
  std::shared_ptr<const Texture> ks;         // local specular weight, colorless (000 §2.9)
  std::shared_ptr<const Texture> shininess;  // n of (R·V)^n or (N·H)^n
  SpecularModel specular_model = SpecularModel::phong;
  std::shared_ptr<const Texture> roughness;  // Cook-Torrance m: rms slope of the facets
  Fresnel fresnel;                           // Cook-Torrance: F (dielectric 1.5 unless set)
  // Path tracing (shading/material_bsdf.h): the facet distribution of the cook_torrance
  // microfacet lobe, Beckmann (the local model's D) or GGX; the local model always uses Beckmann.
  MicrofacetDistribution microfacet = MicrofacetDistribution::beckmann;
  std::shared_ptr<const Texture> kr;   // global specular reflection (000 eq. 5-2)
  std::shared_ptr<const Texture> kt;   // global specular transmission (refraction)
  std::shared_ptr<const Texture> ior;  // index of refraction for kt (000 eq. 5-6)
  // `"thin": true`: kt's dielectric is a thin sheet (a window pane) which light crosses without
  // bending, kt its transmissivity (one pass at normal incidence, Radiance's glass): it reflects and
  // transmits thin_sheet(cos θ, ior, kt) (shading/fresnel.h) in the path tracer, and transmits that
  // in Whitted ray tracing and the shadow rays. The radiosity methods take every surface as opaque
  // (docs/materials.md).
  bool thin = false;
  // `"layered": true` (cook-torrance): the diffuse lies under the specular reflection, as in glTF's
  // metallic-roughness BRDF: for the path tracer the diffuse is kd (1 − F(wo·h)) / π, the light
  // the facet h does not reflect, and the microfacet lobe keeps its weight ks outside the energy
  // rule, its Fresnel factor bounding it (shading/material_bsdf.h).
  bool layered = false;
  Color absorption;  // per unit length inside: exp(-a·d) on shadow rays
  // Emitted exitance E per channel (≥ 0): the self-luminous surfaces of classic radiosity
  // (000 eq. 6-7's E_i); the local model adds it as seen, independent of the lights.
  Color emission;
  // "emission_luminous_flux" — lumens each object of this material sends from each side,
  // spread evenly over its surfaces of it (0: emission as given). The scene loader turns it into
  // each object's `emission` (Φ / its area, by the one efficacy), of this colour (unit luminance).
  double emission_flux = 0;
  Color emission_flux_color;
  Transparency transparency;
  BumpMap bump;

  // A material with every parameter constant: kd 0.8, no specular, no kr/kt.
  Material();

  // Caches what the per-ray tests below read, and at()'s result when no parameter is textured;
  // called by Scene::prepare() (and again whenever a parameter's texture is replaced).
  void prepare();

  SurfaceProperties at(const SurfaceHit& hit) const;
  // kt alone (scaled as in at() where a textured kr + kt exceeds 1), for shadow rays.
  double transmission_at(const SurfaceHit& hit) const;
  // Whether kr or kt can be non-zero anywhere, and whether light passes at all (refraction
  // or the see-through blend).
  bool has_reflection() const { return reflects_; }
  bool has_refraction() const { return refracts_; }
  bool lets_light_through() const { return refracts_ || transparency.active(); }

 private:
  bool reflects_ = false, refracts_ = false;
  // Every parameter constant: at() is the same everywhere (seven virtual texture calls per path
  // vertex saved: 3 % of a path-traced Cornell box).
  bool constant_ = false;
  SurfaceProperties constant_properties_;
};

std::shared_ptr<const Texture> constant_texture(double value);
std::shared_ptr<const Texture> constant_texture(const Color& value);

}  // namespace candela
