// The lobes of a Bsdf (see bsdf.h). Every non-delta lobe is written in the canonical local
// frame: z the shading normal flipped to wo's side (reflection is two-sided), wo.z > 0:
//   lambert     f = ρ/π                                     sampled ∝ cos θ_i
//   phong       f = ks (n + 2)/(2π) cos^n α, α = ∠(wi, r)   sampled ∝ cos^n α about r, the
//               (Lafortune & Willems 1994's normalisation:   mirror of wo; samples under the
//               albedo ks at normal incidence, less else)    surface are rejected (pdf 0 there)
//   microfacet  f = ks D(h) G(wo, wi) F(wi·h) / (4 cos θ_o cos θ_i), h = (wo + wi)/|wo + wi|
//               D Beckmann or GGX with roughness α (normalised: ∫D cos θ_h dω = 1);
//               G the height-correlated Smith masking-shadowing 1/(1 + Λ(wo) + Λ(wi)) (Heitz
//               2014, eq. 99), Λ exact for GGX and Walter et al. 2007's rational fit for
//               Beckmann; F the lobe's Fresnel per channel (fresnel.h);
//               h sampled ∝ D(h) cos θ_h, wi = reflect(wo, h), pdf = D cos θ_h / (4 wo·h).
// The delta lobes (mirror, dielectric) are handled in Bsdf::sample only.
#include "shading/bsdf.h"

#include <algorithm>
#include <cmath>

#include "math/constants.h"
#include "sampling/warps.h"
#include "shading/fresnel.h"
#include "shading/optics.h"

namespace candela {

ShadingFrame ShadingFrame::from_normal(const Vec3& n) {
  ShadingFrame frame;
  frame.n = n;
  orthonormal_basis(n, frame.s, frame.t);  // Duff et al. 2017: branchless, deterministic in n
  return frame;
}

namespace {

bool is_delta(LobeType type) {
  return type == LobeType::mirror || type == LobeType::dielectric || type == LobeType::thin_dielectric;
}

double selection_weight(const BsdfLobe& lobe) {
  return std::max(0.0, lobe.weight.average());
}

// The mirror direction of a local direction about the local normal +z.
Vec3 mirror_local(const Vec3& w) {
  return {-w.x, -w.y, w.z};
}

// wo, wi in the canonical local frame of the reflection lobes; false where no reflection lobe
// can connect them: on opposite sides of the geometric normal (light-leak guard, unless the
// sides are the shading normal's), or wi under the shading hemisphere of wo.
bool reflection_pair(const ShadingFrame& frame, const Vec3& geometric, bool sides_by_shading_normal,
                     const Vec3& wo, const Vec3& wi, Vec3& local_wo, Vec3& local_wi) {
  if (!sides_by_shading_normal && !(dot(wo, geometric) * dot(wi, geometric) > 0)) return false;
  local_wo = frame.to_local(wo);
  local_wi = frame.to_local(wi);
  if (local_wo.z < 0) {
    local_wo.z = -local_wo.z;
    local_wi.z = -local_wi.z;
  }
  return local_wo.z > 0 && local_wi.z > 0;
}

// --- microfacet pieces -------------------------------------------------------------------

// D(m)·cos θ_m, the density the microfacet warps draw m with.
double microfacet_normal_pdf(const BsdfLobe& lobe, const Vec3& m) {
  return lobe.distribution == MicrofacetDistribution::ggx ? ggx_pdf(m, lobe.alpha)
                                                          : beckmann_pdf(m, lobe.alpha);
}

// Smith's Λ for a local direction w (w.z > 0).
double smith_lambda(const BsdfLobe& lobe, const Vec3& w) {
  const double sin2 = w.x * w.x + w.y * w.y;
  if (sin2 <= 0) return 0;
  const double tan2 = sin2 / (w.z * w.z);
  if (lobe.distribution == MicrofacetDistribution::ggx)
    return (-1 + std::sqrt(1 + lobe.alpha * lobe.alpha * tan2)) / 2;
  const double a = 1 / (lobe.alpha * std::sqrt(tan2));
  if (a >= 1.6) return 0;
  return (1 - 1.259 * a + 0.396 * a * a) / (3.535 * a + 2.181 * a * a);
}

// --- one non-delta lobe in the canonical frame -------------------------------------------

Color lobe_f(const BsdfLobe& lobe, const Vec3& wo, const Vec3& wi) {
  switch (lobe.type) {
    case LobeType::lambert: {
      if (!lobe.beneath_facets) return lobe.weight * kInvPi;
      // glTF 2.0's fresnel_mix: the diffuse beneath gets what the facet h between wo and wi does not
      // reflect, 1 − F(wo·h).
      const Vec3 sum = wo + wi;
      const double sum_length = length(sum);
      if (!(sum_length > 0)) return {};
      const double cos_h = std::fabs(dot(wo, sum / sum_length));
      return lobe.weight * max(Color(1) - lobe.fresnel.reflectance(cos_h), Color(0)) * kInvPi;
    }
    case LobeType::phong: {
      const double cos_alpha = dot(wi, mirror_local(wo));
      if (!(cos_alpha > 0)) return {};
      return lobe.weight * ((lobe.exponent + 2) / (2 * kPi) * std::pow(cos_alpha, lobe.exponent));
    }
    case LobeType::microfacet: {
      const Vec3 sum = wo + wi;
      const double sum_length = length(sum);
      if (!(sum_length > 0)) return {};
      const Vec3 h = sum / sum_length;
      const double cos_h = dot(wi, h);
      if (!(cos_h > 0) || !(h.z > 0)) return {};
      const double D = microfacet_normal_pdf(lobe, h) / h.z;
      const double G = 1 / (1 + smith_lambda(lobe, wo) + smith_lambda(lobe, wi));
      return lobe.weight * lobe.fresnel.reflectance(cos_h) * (D * G / (4 * wo.z * wi.z));
    }
    case LobeType::mirror:
    case LobeType::dielectric:
    case LobeType::thin_dielectric:
      return {};
  }
  return {};
}

double lobe_pdf(const BsdfLobe& lobe, const Vec3& wo, const Vec3& wi) {
  switch (lobe.type) {
    case LobeType::lambert:
      return cosine_hemisphere_pdf(wi);
    case LobeType::phong: {
      const double cos_alpha = dot(wi, mirror_local(wo));
      if (!(cos_alpha > 0)) return 0;
      return (lobe.exponent + 1) / (2 * kPi) * std::pow(cos_alpha, lobe.exponent);
    }
    case LobeType::microfacet: {
      const Vec3 sum = wo + wi;
      const double sum_length = length(sum);
      if (!(sum_length > 0)) return 0;
      const Vec3 h = sum / sum_length;
      const double cos_h = dot(wo, h);
      if (!(cos_h > 0)) return 0;
      return microfacet_normal_pdf(lobe, h) / (4 * cos_h);
    }
    case LobeType::mirror:
    case LobeType::dielectric:
    case LobeType::thin_dielectric:
      return 0;
  }
  return 0;
}

// Draws a local wi from the lobe; false when the draw lands under the surface.
bool lobe_sample(const BsdfLobe& lobe, const Vec3& wo, const Vec2& u, Vec3& wi) {
  switch (lobe.type) {
    case LobeType::lambert:
      wi = square_to_cosine_hemisphere(u);
      break;
    case LobeType::phong:
      wi = ShadingFrame::from_normal(mirror_local(wo)).to_world(square_to_power_cosine(u, lobe.exponent));
      break;
    case LobeType::microfacet: {
      const Vec3 m = lobe.distribution == MicrofacetDistribution::ggx ? square_to_ggx(u, lobe.alpha)
                                                                      : square_to_beckmann(u, lobe.alpha);
      const double cos_m = dot(wo, m);
      if (!(cos_m > 0)) return false;
      wi = 2 * cos_m * m - wo;
      break;
    }
    case LobeType::mirror:
    case LobeType::dielectric:
    case LobeType::thin_dielectric:
      return false;
  }
  return wi.z > 0;
}

}  // namespace

void Bsdf::add(const BsdfLobe& lobe) {
  if (count_ >= kMaxBsdfLobes || lobe.weight.is_black()) return;
  lobes_[count_++] = lobe;
}

void Bsdf::conserve_energy() {
  for (int c = 0; c < 3; ++c) {
    double sum = 0;
    for (int i = 0; i < count_; ++i) sum += std::max(0.0, lobes_[i].weight[c]);
    if (sum > 1)
      for (int i = 0; i < count_; ++i) lobes_[i].weight[c] /= sum;
  }
}

bool Bsdf::has_non_delta() const {
  for (int i = 0; i < count_; ++i)
    if (!is_delta(lobes_[i].type)) return true;
  return false;
}

Color Bsdf::evaluate(const Vec3& wo, const Vec3& wi) const {
  Vec3 local_wo, local_wi;
  if (!reflection_pair(frame_, geometric_, sides_by_shading_normal_, wo, wi, local_wo, local_wi)) return {};
  Color f;
  for (int i = 0; i < count_; ++i)
    if (!is_delta(lobes_[i].type)) f += lobe_f(lobes_[i], local_wo, local_wi);
  return f;
}

double Bsdf::pdf(const Vec3& wo, const Vec3& wi) const {
  double total = 0;
  for (int i = 0; i < count_; ++i) total += selection_weight(lobes_[i]);
  if (!(total > 0)) return 0;
  Vec3 local_wo, local_wi;
  if (!reflection_pair(frame_, geometric_, sides_by_shading_normal_, wo, wi, local_wo, local_wi)) return 0;
  double density = 0;
  for (int i = 0; i < count_; ++i)
    if (!is_delta(lobes_[i].type))
      density += selection_weight(lobes_[i]) / total * lobe_pdf(lobes_[i], local_wo, local_wi);
  return density;
}

bool Bsdf::sample(const Vec3& wo, double u_lobe, const Vec2& u, BsdfSample& sample) const {
  double total = 0;
  for (int i = 0; i < count_; ++i) total += selection_weight(lobes_[i]);
  if (!(total > 0)) return false;
  // The lobe whose share of [0, total) holds u_lobe·total (the last non-zero one past rounding).
  int chosen = -1;
  double cumulative = 0;
  const double target = u_lobe * total;
  for (int i = 0; i < count_; ++i) {
    const double w = selection_weight(lobes_[i]);
    if (w <= 0) continue;
    chosen = i;
    cumulative += w;
    if (target < cumulative) break;
  }
  const BsdfLobe& lobe = lobes_[chosen];
  const double probability = selection_weight(lobe) / total;
  sample = BsdfSample{};

  const double cos_geometric_o = dot(wo, geometric_);
  if (cos_geometric_o == 0) return false;
  const Vec3 local_wo = frame_.to_local(wo);

  if (lobe.type == LobeType::mirror) {
    const Vec3 wi = frame_.to_world(mirror_local(local_wo));
    if (!(dot(wi, geometric_) * cos_geometric_o > 0)) return false;  // would leak through
    sample.wi = wi;
    sample.weight = lobe.weight / probability;
    sample.delta = true;
    return true;
  }

  if (lobe.type == LobeType::dielectric) {
    // Smooth glass: reflect with probability F, refract with 1 − F, so the Fresnel factor
    // cancels against its probability and the weight is kt either way. Outside is the
    // geometric normal's side; Snell's law and F use the shading normal turned to wo.
    const bool entering = cos_geometric_o > 0;
    const double eta = entering ? lobe.ior : 1 / lobe.ior;  // n_t / n_i
    const double cos_o = std::fabs(local_wo.z);
    const double F = fresnel_unpolarized(cos_o, eta);  // 1 past the critical angle (TIR)
    sample.delta = true;
    if (u.x < F) {
      const Vec3 wi = frame_.to_world(mirror_local(local_wo));
      if (!(dot(wi, geometric_) * cos_geometric_o > 0)) return false;
      sample.wi = wi;
      sample.weight = lobe.weight / probability;
      return true;
    }
    Vec3 local_wi;
    const Vec3 normal{0, 0, local_wo.z >= 0 ? 1.0 : -1.0};
    if (!refract(local_wo, normal, 1 / eta, local_wi)) return false;  // cannot happen: F = 1 there
    const Vec3 wi = normalize(frame_.to_world(local_wi));
    if (!(dot(wi, geometric_) * cos_geometric_o < 0)) return false;  // must cross the surface
    sample.wi = wi;
    // Radiance is not conserved across the interface, L/η² is (Veach 1997 §5.2; pbrt's
    // TransportMode::Radiance): the radiance carried from wi's side to wo's is scaled by
    // (n_o/n_i)² = 1/η². A path tracer's Russian roulette undoes this with η² (sample.eta).
    sample.weight = lobe.weight / (probability * eta * eta);
    sample.transmission = true;
    sample.eta = eta;
    return true;
  }

  if (lobe.type == LobeType::thin_dielectric) {
    // A thin sheet (shading/fresnel.h): reflect R, pass straight through T, per channel, of
    // transmissivity kt; the rest is absorbed. Reflection is chosen with probability R/(R + T)
    // (channel means), so the weights are R + T either way for a grey sheet, 1 when lossless. Both
    // faces are alike, and no index changes across it: no 1/η², no η for Russian roulette.
    const SheetColors sheet = thin_sheet(std::fabs(local_wo.z), lobe.ior, lobe.weight);
    const double reflected = sheet.reflectance.average(), passed = sheet.transmittance.average();
    if (!(reflected + passed > 0)) return false;
    const double p_reflect = reflected / (reflected + passed);
    sample.delta = true;
    if (u.x < p_reflect) {
      const Vec3 wi = frame_.to_world(mirror_local(local_wo));
      if (!(dot(wi, geometric_) * cos_geometric_o > 0)) return false;
      sample.wi = wi;
      sample.weight = sheet.reflectance / (probability * p_reflect);
      return true;
    }
    sample.wi = -wo;
    sample.weight = sheet.transmittance / (probability * (1 - p_reflect));
    sample.transmission = true;
    sample.passthrough = true;
    return true;
  }

  // A non-delta lobe: draw in the canonical frame, then weigh with the whole mixture.
  const bool flipped = local_wo.z < 0;
  const Vec3 canonical_wo{local_wo.x, local_wo.y, std::fabs(local_wo.z)};
  if (!(canonical_wo.z > 0)) return false;
  Vec3 local_wi;
  if (!lobe_sample(lobe, canonical_wo, u, local_wi)) return false;
  if (flipped) local_wi.z = -local_wi.z;
  const Vec3 wi = frame_.to_world(local_wi);
  const double density = pdf(wo, wi);
  if (!(density > 0)) return false;
  const Color f = evaluate(wo, wi);
  if (f.is_black()) return false;
  sample.wi = wi;
  sample.pdf = density;
  sample.weight = f * (std::fabs(dot(wi, frame_.n)) / density);
  return true;
}

}  // namespace candela
