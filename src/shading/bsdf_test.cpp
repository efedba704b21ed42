// The BSDF lobes: χ² of sample() against pdf(), weights consistent with evaluate()/pdf(),
// reciprocity, albedos (white furnace), the dielectric's Fresnel split, Snell's law and total
// internal reflection, the thin sheet's split, energy conservation and the geometric-normal light-leak
// guard.
#include "shading/bsdf.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "chi_square.h"
#include "math/constants.h"
#include "math/pcg32.h"
#include "sampling/warps.h"
#include "shading/cook_torrance.h"
#include "shading/fresnel.h"

namespace candela {
namespace {

constexpr int kBsdfChiSquareTests = 17;  // every sphere_chi_square call below
const double kBsdfSignificance = test::sidak_significance(0.01, kBsdfChiSquareTests);
constexpr int kBsdfSamples = 100000;
const Vec3 kUp{0, 0, 1};

// A direction at polar angle θ (radians) from +z, azimuth φ.
Vec3 direction(double theta, double phi = 0.4) {
  return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}

Vec3 in_frame(const ShadingFrame& frame, double theta, double phi = 0.4) {
  return frame.to_world(direction(theta, phi));
}

Bsdf flat_bsdf() {
  return Bsdf(ShadingFrame::from_normal(kUp), kUp);
}

BsdfLobe lambert(double rho) {
  BsdfLobe lobe;
  lobe.type = LobeType::lambert;
  lobe.weight = Color(rho);
  return lobe;
}
BsdfLobe phong(double ks, double exponent) {
  BsdfLobe lobe;
  lobe.type = LobeType::phong;
  lobe.weight = Color(ks);
  lobe.exponent = exponent;
  return lobe;
}
BsdfLobe microfacet(double ks, double alpha, MicrofacetDistribution distribution, Color ior = Color(1.5)) {
  BsdfLobe lobe;
  lobe.type = LobeType::microfacet;
  lobe.weight = Color(ks);
  lobe.alpha = alpha;
  lobe.distribution = distribution;
  lobe.fresnel = Fresnel::dielectric(ior);
  return lobe;
}
BsdfLobe mirror(double kr) {
  BsdfLobe lobe;
  lobe.type = LobeType::mirror;
  lobe.weight = Color(kr);
  return lobe;
}
BsdfLobe dielectric(double kt, double ior, LobeType type = LobeType::dielectric) {
  BsdfLobe lobe;
  lobe.type = type;
  lobe.weight = Color(kt);
  lobe.ior = ior;
  return lobe;
}

// χ² of the non-delta directions sample() draws against pdf() (delta draws decline).
void expect_sampling_matches_pdf(const Bsdf& bsdf, const Vec3& wo, uint64_t seed) {
  SCOPED_TRACE(testing::Message() << "wo " << wo);
  const auto result = test::sphere_chi_square(
      [&](Pcg32& rng, Vec3& wi) {
        BsdfSample s;
        const double u_lobe = rng.next_double();
        const double u0 = rng.next_double();
        if (!bsdf.sample(wo, u_lobe, {u0, rng.next_double()}, s) || s.delta) return false;
        wi = s.wi;
        return true;
      },
      [&](const Vec3& wi) { return bsdf.pdf(wo, wi); }, kBsdfSamples, seed);
  EXPECT_GT(result.p_value, kBsdfSignificance) << result.message;
  // The p-values land in the XML report (--gtest_output=xml), one per seed.
  testing::Test::RecordProperty("p_value_seed_" + std::to_string(seed), std::to_string(result.p_value));
}

// ∫ f(wo, wi)·cos θ_i dωi (red channel) over the upper hemisphere, for wo above.
double albedo(const Bsdf& bsdf, const Vec3& wo, int phi_bins = 24) {
  test::SphereGrid grid;
  grid.theta_max = kPi / 2;
  grid.theta_bins = 48;
  grid.phi_bins = phi_bins;
  grid.subdivisions = 2;
  return test::integrate_over_sphere([&](const Vec3& wi) { return bsdf.evaluate(wo, wi).r * wi.z; }, grid);
}

// The same by Monte Carlo with the BSDF's own sampling (mean weight; failed draws count 0).
double sampled_albedo(const Bsdf& bsdf, const Vec3& wo, Pcg32& rng, int count = 20000) {
  double sum = 0;
  for (int k = 0; k < count; ++k) {
    BsdfSample s;
    const double u_lobe = rng.next_double();
    const double u0 = rng.next_double();
    if (bsdf.sample(wo, u_lobe, {u0, rng.next_double()}, s)) sum += s.weight.r;
  }
  return sum / count;
}

// --- χ²: sample() against pdf() ----------------------------------------------------------

TEST(BsdfChiSquare, Lambert) {
  Bsdf bsdf = flat_bsdf();
  bsdf.add(lambert(0.7));
  expect_sampling_matches_pdf(bsdf, direction(0.3), 100);
}

TEST(BsdfChiSquare, Phong) {
  uint64_t seed = 110;
  for (const auto& [exponent, theta] :
       std::vector<std::pair<double, double>>{{1, 30}, {10, 0}, {10, 60}, {100, 45}, {100, 80}}) {
    SCOPED_TRACE(testing::Message() << "n " << exponent << " θo " << theta);
    Bsdf bsdf = flat_bsdf();
    bsdf.add(phong(0.5, exponent));
    expect_sampling_matches_pdf(bsdf, direction(degrees_to_radians(theta)), seed++);
  }
}

TEST(BsdfChiSquare, Microfacet) {
  uint64_t seed = 120;
  for (const auto distribution : {MicrofacetDistribution::beckmann, MicrofacetDistribution::ggx})
    for (const auto& [alpha, theta] :
         std::vector<std::pair<double, double>>{{0.1, 20}, {0.3, 50}, {0.5, 0}, {0.8, 80}}) {
      SCOPED_TRACE(testing::Message() << (distribution == MicrofacetDistribution::ggx ? "GGX" : "Beckmann")
                                      << " α " << alpha << " θo " << theta);
      Bsdf bsdf = flat_bsdf();
      bsdf.add(microfacet(1, alpha, distribution));
      expect_sampling_matches_pdf(bsdf, direction(degrees_to_radians(theta)), seed++);
    }
}

TEST(BsdfChiSquare, MixtureInATiltedFrame) {
  // Lambert + GGX about a tilted normal, and the same with a mirror lobe taking a share of
  // the draws (pdf() then integrates to the non-delta share).
  const Vec3 normal = normalize(Vec3{0.3, -0.2, 1});
  const ShadingFrame frame = ShadingFrame::from_normal(normal);
  Bsdf bsdf(frame, normal);
  bsdf.add(lambert(0.5));
  bsdf.add(microfacet(0.5, 0.2, MicrofacetDistribution::ggx));
  expect_sampling_matches_pdf(bsdf, in_frame(frame, degrees_to_radians(40)), 130);
  bsdf.add(mirror(0.3));
  expect_sampling_matches_pdf(bsdf, in_frame(frame, degrees_to_radians(40)), 131);
}

TEST(BsdfChiSquare, SeenFromBehind) {
  // wo under the surface (and the geometric normal): the lobes work in the flipped frame.
  Bsdf bsdf = flat_bsdf();
  bsdf.add(lambert(0.4));
  bsdf.add(phong(0.4, 20));
  expect_sampling_matches_pdf(bsdf, direction(degrees_to_radians(180 - 35)), 140);
}

// --- consistency -------------------------------------------------------------------------

TEST(Bsdf, SampleWeightIsEvaluateTimesCosineOverPdf) {
  const Vec3 normal = normalize(Vec3{-0.1, 0.2, 1});
  const ShadingFrame frame = ShadingFrame::from_normal(normal);
  std::vector<Bsdf> bsdfs;
  for (int k = 0; k < 4; ++k) bsdfs.emplace_back(frame, normal);
  bsdfs[0].add(lambert(0.6));
  bsdfs[1].add(phong(0.8, 30));
  bsdfs[2].add(microfacet(0.9, 0.25, MicrofacetDistribution::beckmann, Color(1.5, 2.0, 3.0)));
  bsdfs[3].add(lambert(0.3));
  bsdfs[3].add(phong(0.2, 5));
  bsdfs[3].add(microfacet(0.3, 0.4, MicrofacetDistribution::ggx));
  bsdfs[3].add(mirror(0.1));
  Pcg32 rng(5, 6);
  int checked = 0;
  for (const Bsdf& bsdf : bsdfs)
    for (const double theta : {0.1, 0.7, 1.3, kPi - 0.8}) {
      const Vec3 wo = in_frame(frame, theta, 1.1);
      for (int k = 0; k < 500; ++k) {
        BsdfSample s;
        const double u_lobe = rng.next_double();
        const double u0 = rng.next_double();
        if (!bsdf.sample(wo, u_lobe, {u0, rng.next_double()}, s) || s.delta) continue;
        ++checked;
        ASSERT_NEAR(length(s.wi), 1.0, 1e-12);
        const double density = bsdf.pdf(wo, s.wi);
        ASSERT_GT(density, 0);
        EXPECT_NEAR(s.pdf, density, 1e-12 * density);
        const Color expected = bsdf.evaluate(wo, s.wi) * (std::fabs(dot(s.wi, normal)) / density);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(s.weight[c], expected[c], 1e-12 * (1 + expected[c]));
        EXPECT_FALSE(s.transmission);
        EXPECT_EQ(s.eta, 1.0);
      }
    }
  EXPECT_GT(checked, 5000);
}

TEST(Bsdf, Reciprocity) {
  std::vector<Bsdf> bsdfs(4, flat_bsdf());
  bsdfs[0].add(lambert(0.8));
  bsdfs[1].add(phong(0.7, 12));
  bsdfs[2].add(microfacet(1, 0.3, MicrofacetDistribution::beckmann, Color(1.3, 1.8, 2.5)));
  bsdfs[3].add(microfacet(1, 0.15, MicrofacetDistribution::ggx));
  Pcg32 rng(11, 12);
  for (const Bsdf& bsdf : bsdfs)
    for (int k = 0; k < 300; ++k) {
      const Vec3 wo = square_to_uniform_hemisphere({rng.next_double(), rng.next_double()});
      const Vec3 wi = square_to_uniform_hemisphere({rng.next_double(), rng.next_double()});
      const Color forward = bsdf.evaluate(wo, wi), backward = bsdf.evaluate(wi, wo);
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(forward[c], backward[c], 1e-12 * (1 + forward[c]));
    }
}

TEST(Bsdf, ReflectionIsTwoSided) {
  // The same lobes seen from behind: f(wo, wi) = f of the mirrored pair above.
  Bsdf bsdf = flat_bsdf();
  bsdf.add(lambert(0.3));
  bsdf.add(phong(0.3, 8));
  bsdf.add(microfacet(0.3, 0.3, MicrofacetDistribution::ggx));
  const Vec3 wo = direction(0.5, 0.2), wi = direction(0.9, 2.5);
  const Vec3 wo_below{wo.x, wo.y, -wo.z}, wi_below{wi.x, wi.y, -wi.z};
  EXPECT_NEAR(bsdf.evaluate(wo_below, wi_below).g, bsdf.evaluate(wo, wi).g, 1e-14);
  EXPECT_NEAR(bsdf.pdf(wo_below, wi_below), bsdf.pdf(wo, wi), 1e-14);
  EXPECT_GT(bsdf.evaluate(wo, wi).g, 0);
}

// --- albedos -----------------------------------------------------------------------------

TEST(Bsdf, WhiteLambertFurnaceReflectsOne) {
  Bsdf bsdf = flat_bsdf();
  bsdf.add(lambert(1));
  const Vec3 wo = direction(0.6);
  // Monte Carlo with uniform hemisphere directions (not the lobe's own sampling).
  Pcg32 rng(21, 22);
  constexpr int kCount = 100000;
  double sum = 0;
  for (int k = 0; k < kCount; ++k) {
    const Vec3 wi = square_to_uniform_hemisphere({rng.next_double(), rng.next_double()});
    sum += bsdf.evaluate(wo, wi).r * wi.z / uniform_hemisphere_pdf(wi);
  }
  EXPECT_NEAR(sum / kCount, 1.0, 0.01);
  // The lobe's own sampling carries exactly 1.
  for (int k = 0; k < 100; ++k) {
    BsdfSample s;
    ASSERT_TRUE(bsdf.sample(wo, rng.next_double(), {rng.next_double(), rng.next_double()}, s));
    EXPECT_NEAR(s.weight.r, 1.0, 1e-12);
  }
  EXPECT_NEAR(albedo(bsdf, wo), 1.0, 1e-4);
}

TEST(Bsdf, NormalizedPhongAlbedo) {
  for (const double exponent : {1.0, 10.0, 100.0}) {
    SCOPED_TRACE(exponent);
    Bsdf bsdf = flat_bsdf();
    bsdf.add(phong(0.6, exponent));
    // At normal incidence the mirror direction is the normal: the albedo is ks exactly.
    EXPECT_NEAR(albedo(bsdf, kUp), 0.6, 1e-3);
    // Off normal, part of the lobe is cut off by the horizon and cos θ_i < cos α: below ks.
    double previous = 0.6;
    for (const double theta : {30.0, 60.0, 85.0}) {
      const double a = albedo(bsdf, direction(degrees_to_radians(theta)));
      EXPECT_LT(a, previous + 1e-6) << theta;
      EXPECT_GT(a, 0);
      previous = a;
    }
  }
  // For a sharp lobe the albedo tends to ks·cos θ_o (the lobe sits at the mirror direction).
  Bsdf sharp = flat_bsdf();
  sharp.add(phong(0.6, 2000));
  EXPECT_NEAR(albedo(sharp, direction(degrees_to_radians(45)), 192), 0.6 * std::cos(degrees_to_radians(45)),
              2e-3);
}

TEST(Bsdf, MicrofacetAlbedoNeverExceedsOne) {
  // A Fresnel index so large that F = 1: the albedo is the masking-shadowing loss alone. With
  // the visible-normal density, albedo = ∫ D_wo(h)·G2/G1(wo) dh ≤ 1 (exact for GGX's Λ).
  Pcg32 rng(41, 42);
  for (const auto distribution : {MicrofacetDistribution::beckmann, MicrofacetDistribution::ggx}) {
    for (const double alpha : {0.1, 0.3, 0.6, 1.0}) {
      for (const double theta : {0.0, 40.0, 75.0, 88.0}) {
        SCOPED_TRACE(testing::Message() << int(distribution) << " α " << alpha << " θo " << theta);
        Bsdf bsdf = flat_bsdf();
        bsdf.add(microfacet(1, alpha, distribution, Color(1e8)));
        // Importance-sampled: the lobe grows too sharp at grazing angles for the quadrature.
        const double a = sampled_albedo(bsdf, direction(degrees_to_radians(theta)), rng);
        EXPECT_LE(a, 1.0 + 0.01);
        if (alpha <= 0.1 && theta <= 40) {
          EXPECT_GT(a, 0.97);  // smooth: little is lost
        }
        EXPECT_GT(a, 0.3);
      }
    }
  }
  // With glass's Fresnel (index 1.5) at normal incidence a smooth surface reflects about F(0) = 0.04.
  Bsdf glass = flat_bsdf();
  glass.add(microfacet(1, 0.05, MicrofacetDistribution::ggx, Color(1.5)));
  EXPECT_NEAR(albedo(glass, kUp), 0.04, 2e-3);
}

// --- delta lobes -------------------------------------------------------------------------

TEST(Bsdf, MirrorReflectsAboutTheShadingNormal) {
  Bsdf bsdf = flat_bsdf();
  bsdf.add(mirror(0.7));
  bsdf.add(lambert(0.3));
  const Vec3 wo = direction(0.8, 1.0);
  BsdfSample s;
  ASSERT_TRUE(bsdf.sample(wo, 0.1, {0.5, 0.5}, s));  // u_lobe in the mirror's 0.7 share
  EXPECT_TRUE(s.delta);
  EXPECT_EQ(s.pdf, 0.0);
  EXPECT_NEAR(s.weight.r, 0.7 / 0.7, 1e-12);
  EXPECT_NEAR(s.wi.x, -wo.x, 1e-12);
  EXPECT_NEAR(s.wi.y, -wo.y, 1e-12);
  EXPECT_NEAR(s.wi.z, wo.z, 1e-12);
  EXPECT_TRUE(bsdf.evaluate(wo, s.wi).r < 0.3 / kPi + 1e-12);  // evaluate() sees lambert only
  EXPECT_TRUE(bsdf.has_non_delta());
  Bsdf pure = flat_bsdf();
  pure.add(mirror(1));
  EXPECT_FALSE(pure.has_non_delta());
  EXPECT_EQ(pure.pdf(wo, s.wi), 0.0);
}

// Fraction of a fine sweep of u.x that the dielectric reflects, and the two samples.
struct DielectricSplit {
  double reflected_fraction = 0;
  BsdfSample reflection, transmission;
  bool has_reflection = false, has_transmission = false;
};

DielectricSplit sweep(const Bsdf& bsdf, const Vec3& wo) {
  DielectricSplit split;
  constexpr int kSteps = 10000;
  int reflected = 0;
  for (int k = 0; k < kSteps; ++k) {
    BsdfSample s;
    EXPECT_TRUE(bsdf.sample(wo, 0.5, {(k + 0.5) / kSteps, 0.5}, s));
    EXPECT_TRUE(s.delta);
    if (s.transmission) {
      split.transmission = s;
      split.has_transmission = true;
    } else {
      ++reflected;
      split.reflection = s;
      split.has_reflection = true;
    }
  }
  split.reflected_fraction = static_cast<double>(reflected) / kSteps;
  return split;
}

TEST(Bsdf, DielectricSplitsByFresnelAndRefractsBySnell) {
  const double ior = 1.5, kt = 0.9;
  Bsdf bsdf = flat_bsdf();
  bsdf.add(dielectric(kt, ior));
  for (const double theta_deg : {0.0, 30.0, 60.0, 80.0}) {
    SCOPED_TRACE(theta_deg);
    const double theta = degrees_to_radians(theta_deg);
    // Entering from outside (the geometric normal's side).
    const Vec3 wo = direction(theta, 0.7);
    const DielectricSplit split = sweep(bsdf, wo);
    EXPECT_NEAR(split.reflected_fraction, fresnel_unpolarized(std::cos(theta), ior), 2e-4);
    ASSERT_TRUE(split.has_transmission);
    const BsdfSample& t = split.transmission;
    EXPECT_LT(t.wi.z, 0);
    EXPECT_NEAR(t.eta, ior, 1e-15);
    EXPECT_NEAR(t.weight.r, kt / (ior * ior), 1e-12);  // radiance scales by 1/η²
    const double sin_t = std::sqrt(t.wi.x * t.wi.x + t.wi.y * t.wi.y);
    EXPECT_NEAR(ior * sin_t, std::sin(theta), 1e-12);  // Snell
    if (theta_deg > 0) {  // in the plane of incidence, on the far side of the normal
      EXPECT_NEAR(t.wi.x * wo.y - t.wi.y * wo.x, 0, 1e-12);
      EXPECT_LT(t.wi.x * wo.x + t.wi.y * wo.y, 0);
    }
    ASSERT_TRUE(split.has_reflection);
    EXPECT_NEAR(split.reflection.weight.r, kt, 1e-12);
    EXPECT_NEAR(split.reflection.wi.z, wo.z, 1e-12);
    EXPECT_EQ(split.reflection.eta, 1.0);

    // From inside along the refracted ray: the reverse path leaves along wo, with η = 1/ior.
    const Vec3 inside = t.wi;
    const DielectricSplit out = sweep(bsdf, inside);
    EXPECT_NEAR(out.reflected_fraction, fresnel_unpolarized(std::cos(theta), ior), 2e-4);
    ASSERT_TRUE(out.has_transmission);
    EXPECT_NEAR(out.transmission.eta, 1 / ior, 1e-15);
    EXPECT_NEAR(out.transmission.weight.r, kt * ior * ior, 1e-12);
    EXPECT_NEAR(out.transmission.wi.x, wo.x, 1e-12);
    EXPECT_NEAR(out.transmission.wi.y, wo.y, 1e-12);
    EXPECT_NEAR(out.transmission.wi.z, wo.z, 1e-12);
  }
}

TEST(Bsdf, DielectricTotalInternalReflection) {
  const double ior = 1.5;
  Bsdf bsdf = flat_bsdf();
  bsdf.add(dielectric(1, ior));
  const double critical = std::asin(1 / ior);
  for (const double theta : {critical + 0.01, 1.0, 1.4}) {
    const Vec3 wo = direction(kPi - theta);  // inside, beyond the critical angle
    const DielectricSplit split = sweep(bsdf, wo);
    EXPECT_EQ(split.reflected_fraction, 1.0) << theta;
    EXPECT_NEAR(split.reflection.wi.z, wo.z, 1e-12);
    EXPECT_NEAR(split.reflection.weight.r, 1.0, 1e-12);
  }
  // Just inside the critical angle light still leaves.
  EXPECT_LT(sweep(bsdf, direction(kPi - (critical - 0.01))).reflected_fraction, 1.0);
}

TEST(Bsdf, ThinSheetReflectsItsFresnelPartAndPassesTheRestStraightThrough) {
  // kt the sheet's transmissivity: it reflects R and passes T (shading/fresnel.h), reflection
  // chosen with probability R/(R + T) and each sample weighted R + T (the absorbed part lost).
  const double ior = 1.52, kt = 0.8;
  Bsdf bsdf = flat_bsdf();
  bsdf.add(dielectric(kt, ior, LobeType::thin_dielectric));
  EXPECT_TRUE(bsdf.evaluate(direction(0.3), direction(2.5)).is_black());  // delta only
  for (const double theta_deg : {0.0, 30.0, 60.0, 85.0}) {
    SCOPED_TRACE(theta_deg);
    const double theta = degrees_to_radians(theta_deg);
    const SheetSplit sheet = thin_sheet(std::cos(theta), ior, kt);
    const double kept = sheet.reflectance + sheet.transmittance;
    EXPECT_LT(kept, 1);
    // Both faces alike: from above and from below the same split, and no bending either way.
    for (const double side : {1.0, -1.0}) {
      Vec3 wo = direction(theta, 0.7);
      wo.z *= side;
      const DielectricSplit split = sweep(bsdf, wo);
      EXPECT_NEAR(split.reflected_fraction, sheet.reflectance / kept, 2e-4);
      ASSERT_TRUE(split.has_transmission);
      EXPECT_TRUE(split.transmission.passthrough);
      EXPECT_EQ(split.transmission.wi, -wo);
      EXPECT_NEAR(split.transmission.weight.r, kept, 1e-12);  // no 1/η²: the index is the same beyond
      EXPECT_EQ(split.transmission.eta, 1.0);
      ASSERT_TRUE(split.has_reflection);
      EXPECT_FALSE(split.reflection.passthrough);
      EXPECT_NEAR(split.reflection.wi.z, wo.z, 1e-12);
      EXPECT_NEAR(split.reflection.wi.x, -wo.x, 1e-12);
      EXPECT_NEAR(split.reflection.weight.r, kept, 1e-12);
    }
  }
  // A tinted sheet: each channel its own transmittance, reflection chosen by the means.
  Bsdf tinted = flat_bsdf();
  BsdfLobe lobe = dielectric(1, ior, LobeType::thin_dielectric);
  lobe.weight = Color(0.9, 0.5, 0.2);
  tinted.add(lobe);
  const SheetColors sheet = thin_sheet(std::cos(0.5), ior, lobe.weight);
  const double p_reflect = sheet.reflectance.average() / (sheet.reflectance + sheet.transmittance).average();
  const DielectricSplit split = sweep(tinted, direction(0.5));
  EXPECT_NEAR(split.reflected_fraction, p_reflect, 2e-4);
  EXPECT_NEAR(split.transmission.weight.b, sheet.transmittance.b / (1 - p_reflect), 1e-12);
  EXPECT_NEAR(split.reflection.weight.g, sheet.reflectance.g / p_reflect, 1e-12);
}

// --- energy and leaks --------------------------------------------------------------------

TEST(Bsdf, ConserveEnergyScalesOnlyChannelsAboveOne) {
  Bsdf bsdf = flat_bsdf();
  BsdfLobe diffuse = lambert(0);
  diffuse.weight = Color(0.8, 0.2, 0.5);
  bsdf.add(diffuse);
  bsdf.add(phong(0.6, 10));
  bsdf.add(mirror(0.3));
  bsdf.conserve_energy();
  // Red: 0.8 + 0.6 + 0.3 = 1.7 → each / 1.7; green 1.1 → / 1.1; blue 1.4 → / 1.4.
  EXPECT_NEAR(bsdf.lobe(0).weight.r, 0.8 / 1.7, 1e-15);
  EXPECT_NEAR(bsdf.lobe(1).weight.r, 0.6 / 1.7, 1e-15);
  EXPECT_NEAR(bsdf.lobe(2).weight.g, 0.3 / 1.1, 1e-15);
  EXPECT_NEAR(bsdf.lobe(0).weight.b, 0.5 / 1.4, 1e-15);
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(bsdf.lobe(0).weight[c] + bsdf.lobe(1).weight[c] + bsdf.lobe(2).weight[c], 1.0, 1e-15);
  Bsdf dim = flat_bsdf();
  dim.add(lambert(0.3));
  dim.add(phong(0.2, 10));
  dim.conserve_energy();
  EXPECT_EQ(dim.lobe(0).weight, Color(0.3));
  EXPECT_EQ(dim.lobe(1).weight, Color(0.2));
}

TEST(Bsdf, AddDropsBlackLobesAndExtras) {
  Bsdf bsdf = flat_bsdf();
  bsdf.add(lambert(0));
  EXPECT_EQ(bsdf.lobe_count(), 0);
  BsdfSample s;
  EXPECT_FALSE(bsdf.sample(kUp, 0.5, {0.5, 0.5}, s));
  EXPECT_EQ(bsdf.pdf(kUp, kUp), 0.0);
  for (int k = 0; k < kMaxBsdfLobes + 2; ++k) bsdf.add(lambert(0.1));
  EXPECT_EQ(bsdf.lobe_count(), kMaxBsdfLobes);
}

TEST(Bsdf, NoLightLeaksThroughATiltedShadingNormal) {
  // The shading normal leans 40° from the geometric one: wo above both, wi above the shading
  // hemisphere yet under the geometric plane must not connect.
  const Vec3 geometric = kUp;
  const Vec3 shading = direction(degrees_to_radians(40), 0);
  Bsdf bsdf(ShadingFrame::from_normal(shading), geometric);
  bsdf.add(lambert(0.5));
  bsdf.add(phong(0.3, 5));
  bsdf.add(microfacet(0.2, 0.3, MicrofacetDistribution::beckmann));
  const Vec3 wo = direction(degrees_to_radians(20), 0);
  const Vec3 wi = direction(degrees_to_radians(110), 0);  // x > 0: above the shading plane
  ASSERT_GT(dot(wi, shading), 0);
  ASSERT_LT(dot(wi, geometric), 0);
  EXPECT_TRUE(bsdf.evaluate(wo, wi).is_black());
  EXPECT_EQ(bsdf.pdf(wo, wi), 0.0);
  // No sample crosses the geometric plane either.
  Bsdf shiny(ShadingFrame::from_normal(shading), geometric);
  shiny.add(lambert(0.5));
  shiny.add(mirror(0.5));
  Pcg32 rng(31, 32);
  int crossing = 0, sampled = 0;
  for (int k = 0; k < 20000; ++k) {
    BsdfSample s;
    const Vec3 w = direction(degrees_to_radians(80), 2 * kPi * rng.next_double());
    if (!shiny.sample(w, rng.next_double(), {rng.next_double(), rng.next_double()}, s)) continue;
    ++sampled;
    if (dot(s.wi, geometric) <= 0) ++crossing;
  }
  EXPECT_EQ(crossing, 0);
  EXPECT_GT(sampled, 10000);
}

}  // namespace
}  // namespace candela
