// Cook-Torrance (000 §4.2.2; SPEC §7) against hand-computed values, and its place in the local
// model beside Phong and Blinn-Phong.
#include "shading/local_model.h"

#include <gtest/gtest.h>

#include <cmath>

#include "math/constants.h"
#include "shading/cook_torrance.h"

namespace candela {
namespace {

TEST(Beckmann, HandComputedValues) {
  EXPECT_NEAR(beckmann_distribution(1.0, 0.5), 4.0, 1e-15);  // 1/m² at α = 0
  // α = 30°, m = 0.5: exp(−(tan²30°)/m²)/(m² cos⁴30°) = exp(−4/3)/(0.25·0.5625).
  EXPECT_NEAR(beckmann_distribution(std::cos(kPi / 6), 0.5), 1.8744685377118344, 1e-12);
  EXPECT_NEAR(beckmann_distribution(std::cos(kPi / 6), 0.5), std::exp(-4.0 / 3.0) / (0.25 * 0.5625), 1e-12);
  EXPECT_EQ(beckmann_distribution(0.0, 0.5), 0.0);  // facets at 90° do not exist
  // Rougher surfaces spread the lobe: lower peak, higher tail.
  EXPECT_GT(beckmann_distribution(1.0, 0.2), beckmann_distribution(1.0, 0.6));
  EXPECT_LT(beckmann_distribution(std::cos(kPi / 4), 0.2), beckmann_distribution(std::cos(kPi / 4), 0.6));
}

TEST(GeometricAttenuation, UnmaskedMaskedAndShadowed) {
  EXPECT_EQ(geometric_attenuation(1, 1, 1, 1), 1.0);
  // Grazing view: 2(N·H)(N·V)/(V·H) = 2·0.9·0.1/0.5 = 0.36 masks most of the facets.
  EXPECT_NEAR(geometric_attenuation(0.9, 0.1, 0.8, 0.5), 0.36, 1e-15);
  // Grazing light: the shadowing term is the smaller one.
  EXPECT_NEAR(geometric_attenuation(0.9, 0.8, 0.05, 0.5), 0.18, 1e-15);
}

TEST(CookTorrance, MirrorConfigurationByHand) {
  // V = L = N: H = N, D = 1/m², G = 1, F = F(0): k_s = F0 / (π m²).
  const Vec3 N{0, 0, 1};
  const Color ks = cook_torrance(N, N, N, 0.5, Fresnel::dielectric(Color(1.5)));
  EXPECT_NEAR(ks.r, 0.04 * 4 / kPi, 1e-15);
  EXPECT_NEAR(ks.g, ks.r, 0);
}

TEST(CookTorrance, OffSpecularByHand) {
  // L at 60° and V at 0° in the xz plane: H at 30°, V·H = cos 30°.
  const Vec3 N{0, 0, 1};
  const Vec3 V = N;
  const Vec3 L{std::sin(kPi / 3), 0, std::cos(kPi / 3)};
  const double m = 0.4;
  const double cos_alpha = std::cos(kPi / 6);
  const double D = std::exp(-std::pow(std::tan(kPi / 6) / m, 2)) / (m * m * std::pow(cos_alpha, 4));
  const double G = std::min({1.0, 2 * cos_alpha * 1.0 / cos_alpha, 2 * cos_alpha * 0.5 / cos_alpha});
  const double F = fresnel_unpolarized(std::cos(kPi / 6), 1.5);  // fresnel_test.cpp checks it
  const double expected = D * G * F / (kPi * 1.0 * 0.5);
  EXPECT_NEAR(cook_torrance(N, V, L, m, Fresnel::dielectric(Color(1.5))).r, expected, 1e-12);
  // Nothing from below the surface or toward a viewer below it.
  EXPECT_TRUE(cook_torrance(N, V, -L, m, Fresnel::dielectric(Color(1.5))).is_black());
  EXPECT_TRUE(cook_torrance(N, -V, L, m, Fresnel::dielectric(Color(1.5))).is_black());
}

TEST(LocalModel, CookTorranceHighlightTakesTheMaterialsColor) {
  Material material;
  material.specular_model = SpecularModel::cook_torrance;
  material.fresnel = Fresnel::dielectric(Color(3.0, 1.6, 1.3));
  SurfaceProperties at;
  at.kd = Color(0);
  at.ks = 1;
  at.roughness = 0.3;
  const Vec3 N{0, 0, 1};
  const Color I = direct_term(material, at, N, N, N, Color(2));
  // ks·(N·L)·F·D·G/(π(N·V)(N·L)) with D = 1/m², G = 1, N·L = N·V = 1: the color of F(0).
  const double scale = 2 / (kPi * 0.09);
  EXPECT_NEAR(I.r, scale * 0.25, 1e-12);
  EXPECT_NEAR(I.g, scale * std::pow(0.6 / 2.6, 2), 1e-12);
  EXPECT_NEAR(I.b, scale * std::pow(0.3 / 2.3, 2), 1e-12);
  // Phong's highlight is colorless whatever the material.
  material.specular_model = SpecularModel::phong;
  at.shininess = 10;
  const Color phong = direct_term(material, at, N, N, N, Color(2));
  EXPECT_EQ(phong.r, phong.g);
  EXPECT_EQ(phong.g, phong.b);
}

TEST(LocalModel, CookTorranceAddsTheDiffuseTerm) {
  Material material;
  material.specular_model = SpecularModel::cook_torrance;
  SurfaceProperties at;
  at.kd = Color(0.5, 0.25, 0.125);
  at.ks = 0;  // no specular weight: Lambert only
  const Vec3 N{0, 0, 1};
  const Vec3 L = normalize(Vec3{1, 0, 1});
  const Color I = direct_term(material, at, N, N, L, Color(1));
  EXPECT_NEAR(I.r, 0.5 * std::sqrt(0.5), 1e-15);
  EXPECT_NEAR(I.b, 0.125 * std::sqrt(0.5), 1e-15);
}

}  // namespace
}  // namespace candela
