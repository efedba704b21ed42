// The Fresnel factors of shading/fresnel.h: the seed's dielectric (000 §4.2.2) against its own
// sin/tan form, the conductor against the complex amplitudes r_s, r_p computed independently with
// std::complex, and Schlick's form; and the copper that turned bluish at grazing incidence.
#include "shading/fresnel.h"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>

#include "math/constants.h"

namespace candela {
namespace {

// The seed's own form of the unpolarised Fresnel term, with φ the refraction angle.
double seed_fresnel(double theta, double n) {
  const double phi = std::asin(std::sin(theta) / n);
  const double sin_ratio = std::sin(phi - theta) / std::sin(phi + theta);
  const double tan_ratio = std::tan(phi - theta) / std::tan(phi + theta);
  return 0.5 * (sin_ratio * sin_ratio + tan_ratio * tan_ratio);
}

TEST(Fresnel, NormalIncidenceIsSquaredRatio) {
  for (const double n : {1.2, 1.5, 2.0, 3.0}) {
    const double expected = std::pow((n - 1) / (n + 1), 2);
    EXPECT_NEAR(fresnel_unpolarized(1.0, n), expected, 1e-15) << n;
  }
  EXPECT_NEAR(fresnel_unpolarized(1.0, 1.5), 0.04, 1e-15);
}

TEST(Fresnel, MatchesTheSeedsFormulaAtEveryAngle) {
  // 45° on glass: 0.0502399 (from the seed's sin/tan form, computed by hand).
  EXPECT_NEAR(fresnel_unpolarized(std::cos(kPi / 4), 1.5), 0.050239911012235954, 1e-12);
  for (int i = 1; i < 90; ++i) {
    const double theta = i * kPi / 180;
    for (const double n : {1.33, 1.5, 2.4})
      EXPECT_NEAR(fresnel_unpolarized(std::cos(theta), n), seed_fresnel(theta, n), 1e-12)
          << i << "° n = " << n;
  }
  // Grazing incidence reflects everything; rising monotonically toward it.
  EXPECT_NEAR(fresnel_unpolarized(0.0, 1.5), 1.0, 1e-15);
  double previous = 0;
  for (int i = 0; i <= 90; ++i) {
    const double F = fresnel_unpolarized(std::cos(i * kPi / 180), 1.5);
    EXPECT_GE(F, previous - 1e-15);
    previous = F;
  }
}

// A thin lossless sheet (a window pane): each polarisation's r bounces between the faces, 2r/(1 + r)
// comes back. At normal incidence both are ((n − 1)/(n + 1))²: 0.08/1.04 for n = 1.5; at Brewster's
// angle (tan θ = n) r_p = 0, so r_s = 2F (F the unpolarised single-face value) and R = ½ · 2r_s/(1 + r_s).
TEST(Fresnel, ThinSheetSumsTheReflectionsBetweenItsFaces) {
  EXPECT_NEAR(thin_sheet(1.0, 1.5).reflectance, 0.08 / 1.04, 1e-15);
  for (const double n : {1.33, 1.5, 1.52, 2.4}) {
    const double r = fresnel_unpolarized(1.0, n);
    EXPECT_NEAR(thin_sheet(1.0, n).reflectance, 2 * r / (1 + r), 1e-14) << n;
    const double brewster = std::atan(n);
    const double r_s = 2 * fresnel_unpolarized(std::cos(brewster), n);
    EXPECT_NEAR(thin_sheet(std::cos(brewster), n).reflectance, r_s / (1 + r_s), 1e-12) << n;
    // More than one face reflects, less than two faces' worth, and everything at grazing incidence;
    // lossless, what is not reflected goes through.
    for (int degrees = 0; degrees < 90; degrees += 5) {
      const double c = std::cos(degrees * kPi / 180), F = fresnel_unpolarized(c, n);
      const SheetSplit sheet = thin_sheet(c, n);
      EXPECT_GT(sheet.reflectance, F) << n << " at " << degrees << "°";
      EXPECT_LE(sheet.reflectance, 2 * F + 1e-15) << n << " at " << degrees << "°";
      EXPECT_NEAR(sheet.reflectance + sheet.transmittance, 1, 1e-14) << n << " at " << degrees << "°";
    }
    EXPECT_EQ(thin_sheet(0.0, n).reflectance, 1.0);
    EXPECT_EQ(thin_sheet(0.0, n).transmittance, 0.0);
  }
}

// An absorbing sheet: one pass at normal incidence lets the transmissivity t through, and a pass at
// θ_t inside t^(1/cos θ_t). Opaque inside (t = 0), only the first face reflects. CIE 171's 6 mm
// clear glass, 0.87881 through at normal incidence, is n = 1.52 and t = 0.95712.
TEST(Fresnel, AnAbsorbingSheetLosesItsTransmissivityAlongTheSlantedPass) {
  for (int degrees = 0; degrees < 90; degrees += 10) {
    const double c = std::cos(degrees * kPi / 180);
    EXPECT_NEAR(thin_sheet(c, 1.5, 0).reflectance, fresnel_unpolarized(c, 1.5), 1e-15) << degrees;
    EXPECT_EQ(thin_sheet(c, 1.5, 0).transmittance, 0) << degrees;
    const SheetSplit lossless = thin_sheet(c, 1.5), absorbing = thin_sheet(c, 1.5, 0.8);
    EXPECT_LT(absorbing.transmittance, 0.8 * lossless.transmittance + 1e-15) << degrees;  // longer path
    EXPECT_LT(absorbing.reflectance, lossless.reflectance) << degrees;
    EXPECT_GT(absorbing.reflectance, fresnel_unpolarized(c, 1.5)) << degrees;
  }
  // Normal incidence, by hand: r = (0.5/2.5)², T = (1 − r)² t / (1 − r² t²).
  const double r = 0.04, t = 0.8;
  EXPECT_NEAR(thin_sheet(1, 1.5, t).transmittance, (1 - r) * (1 - r) * t / (1 - r * r * t * t), 1e-15);
  EXPECT_NEAR(thin_sheet(1, 1.5, t).reflectance, r + (1 - r) * (1 - r) * r * t * t / (1 - r * r * t * t),
              1e-15);
  // CIE 171's 6 mm clear glass (its curve against the report's: Cie171.ReferencesAgree...).
  EXPECT_NEAR(thin_sheet(1, 1.52, 0.95712).transmittance, 0.87881, 2e-5);
  const SheetColors tinted = thin_sheet(0.5, 1.52, Color(0.9, 0.5, 0.1));
  EXPECT_EQ(tinted.transmittance.g, thin_sheet(0.5, 1.52, 0.5).transmittance);
  EXPECT_EQ(tinted.reflectance.b, thin_sheet(0.5, 1.52, 0.1).reflectance);
}

TEST(Fresnel, PerChannelIndexColorsTheReflectance) {
  const Color F = fresnel_unpolarized(1.0, Color(3.0, 1.6, 1.3));
  EXPECT_NEAR(F.r, 0.25, 1e-15);
  EXPECT_NEAR(F.g, std::pow(0.6 / 2.6, 2), 1e-15);
  EXPECT_NEAR(F.b, std::pow(0.3 / 2.3, 2), 1e-15);
}

// The reflectance of n + iκ from the amplitudes (Born & Wolf §14.2): with N the complex index,
// cos φ = √(1 − sin²θ/N²), r_s = (cos θ − N cos φ)/(cos θ + N cos φ), r_p = (N cos θ − cos φ)/(N cos θ + cos
// φ).
double complex_amplitude_reflectance(double theta, double n, double k) {
  const std::complex<double> N(n, k);
  const double s = std::sin(theta), c = std::cos(theta);
  const std::complex<double> cos_phi = std::sqrt(1.0 - s * s / (N * N));
  const std::complex<double> rs = (c - N * cos_phi) / (c + N * cos_phi);
  const std::complex<double> rp = (N * c - cos_phi) / (N * c + cos_phi);
  return 0.5 * (std::norm(rs) + std::norm(rp));
}

TEST(Fresnel, ConductorMatchesTheComplexAmplitudes) {
  // Copper's n, κ near 650, 550 and 450 nm (Hagemann, Gudat & Kunz 1974), aluminium's at 620 nm, gold's at
  // 620 nm.
  const double indices[][2] = {{0.214, 3.67}, {0.9, 2.6},    {1.169, 2.36},
                               {1.292, 7.28}, {0.487, 3.31}, {2.0, 0.5}};
  for (const auto& [n, k] : indices) {
    EXPECT_NEAR(fresnel_conductor(1.0, n, k), ((n - 1) * (n - 1) + k * k) / ((n + 1) * (n + 1) + k * k),
                1e-14);
    for (int i = 0; i < 90; ++i) {
      const double theta = (i + 0.5) * kPi / 180;
      EXPECT_NEAR(fresnel_conductor(std::cos(theta), n, k), complex_amplitude_reflectance(theta, n, k), 1e-12)
          << "n " << n << " k " << k << " at " << i + 0.5 << "°";
    }
    EXPECT_NEAR(fresnel_conductor(0.0, n, k), 1.0, 1e-15);
  }
}

TEST(Fresnel, ConductorWithoutExtinctionIsTheDielectric) {
  for (const double n : {1.0001, 1.33, 1.5, 2.4, 78.0})
    for (int i = 0; i <= 90; ++i) {
      const double c = std::cos(i * kPi / 180);
      EXPECT_NEAR(fresnel_conductor(c, n, 0), fresnel_unpolarized(c, n), 1e-12) << n << " at " << i << "°";
    }
}

TEST(Fresnel, SchlickRisesFromF0ToOneMonotonically) {
  for (const double f0 : {0.0, 0.04, 0.54, 0.95, 1.0}) {
    EXPECT_DOUBLE_EQ(fresnel_schlick(1.0, f0), f0);
    EXPECT_DOUBLE_EQ(fresnel_schlick(0.0, f0), 1.0);
    EXPECT_DOUBLE_EQ(fresnel_schlick(0.5, f0), f0 + (1 - f0) / 32);
    double previous = f0;
    for (int i = 0; i <= 900; ++i) {
      const double F = fresnel_schlick(std::cos(i * kPi / 1800), f0);
      EXPECT_GE(F, previous);
      previous = F;
    }
  }
}

TEST(Fresnel, EachModelPerChannel) {
  const Color eta(3.0, 1.6, 1.3), k(0.5, 1.0, 2.0), f0(0.9, 0.5, 0.1);
  for (const double c : {1.0, 0.7, 0.2, 0.0}) {
    const Color dielectric = Fresnel::dielectric(eta).reflectance(c);
    const Color conductor = Fresnel::conductor(eta, k).reflectance(c);
    const Color schlick = Fresnel::schlick(f0).reflectance(c);
    for (int channel = 0; channel < 3; ++channel) {
      EXPECT_EQ(dielectric[channel], fresnel_unpolarized(c, eta[channel]));
      EXPECT_EQ(conductor[channel], fresnel_conductor(c, eta[channel], k[channel]));
      EXPECT_EQ(schlick[channel], fresnel_schlick(c, f0[channel]));
    }
  }
  EXPECT_TRUE(Fresnel() == Fresnel::dielectric(Color(1.5)));
}

// The defect this file's models replace: copper given as F0 [0.95, 0.64, 0.54] and turned into
// real indices (1 + √F0)/(1 − √F0) = [78.0, 9.0, 6.54] reflects [0.68, 0.55, 0.60] at 87° — red
// falling, blue above green. Schlick's F0 form and a measured n + iκ both keep copper's order of
// channels and whiten toward grazing incidence.
TEST(Fresnel, CopperWhitensTowardGrazingInsteadOfTurningBlue) {
  const Color f0(0.95, 0.64, 0.54);
  Color derived_index;
  for (int c = 0; c < 3; ++c) derived_index[c] = (1 + std::sqrt(f0[c])) / (1 - std::sqrt(f0[c]));
  const Color dipped = Fresnel::dielectric(derived_index).reflectance(std::cos(87 * kPi / 180));
  EXPECT_LT(dipped.r, 0.7);       // the Brewster dip of the old model, for the record
  EXPECT_GT(dipped.b, dipped.g);  // bluish

  // Copper's n + iκ at about 650, 550 and 450 nm (Hagemann, Gudat & Kunz 1974).
  const Fresnel measured = Fresnel::conductor(Color(0.214, 0.9, 1.169), Color(3.67, 2.6, 2.36));
  for (const Fresnel& fresnel : {Fresnel::schlick(f0), measured}) {
    const Color normal = fresnel.reflectance(1);
    for (int i = 0; i <= 89; ++i) {
      const Color F = fresnel.reflectance(std::cos(i * kPi / 180));
      EXPECT_GE(F.r, F.g) << i << "°";
      EXPECT_GE(F.g, F.b) << i << "°";
      if (i >= 60) {  // paler than at normal incidence: the spread of channels shrinks
        EXPECT_LT((F.r - F.b) / F.r, (normal.r - normal.b) / normal.r) << i << "°";
      }
    }
    const Color grazing = fresnel.reflectance(std::cos(89 * kPi / 180));
    EXPECT_GT(grazing.b, 0.9);
  }
}

}  // namespace
}  // namespace candela
