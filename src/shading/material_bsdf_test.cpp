// The classic material's parameters as BSDF lobes (material_bsdf.h). The scene key "microfacet"
// is tests/material_scene_test.cpp.
#include "shading/material_bsdf.h"

#include <gtest/gtest.h>

#include <cmath>

#include "math/constants.h"
#include "shading/checkerboard_texture.h"

namespace candela {
namespace {

SurfaceHit flat_hit() {
  SurfaceHit hit;
  hit.geometric_normal = {0, 0, 1};
  hit.shading_normal = {0, 0, 1};
  return hit;
}

Bsdf bsdf_of(const Material& material, const Vec3& shading_normal = {0, 0, 1}) {
  const SurfaceHit hit = flat_hit();
  return make_bsdf(material, material.at(hit), hit, shading_normal);
}

// glTF's metallic-roughness BRDF: the diffuse beneath gets 1 − F(wo·h), the facets keep their weight
// outside the energy rule (kd + ks = 1.8 here would have divided both by 1.8).
TEST(MaterialBsdf, LayeredDiffuseLiesUnderTheFacetsFresnel) {
  Material material;
  material.specular_model = SpecularModel::cook_torrance;
  material.kd = constant_texture(0.8);
  material.ks = constant_texture(1.0);
  material.roughness = constant_texture(0.3);
  material.fresnel = Fresnel::schlick(Color(0.04));
  material.microfacet = MicrofacetDistribution::ggx;
  material.layered = true;
  material.prepare();
  const Bsdf layered = bsdf_of(material);
  ASSERT_EQ(layered.lobe_count(), 2);
  EXPECT_EQ(layered.lobe(0).weight.g, 0.8);
  EXPECT_EQ(layered.lobe(1).type, LobeType::microfacet);
  EXPECT_EQ(layered.lobe(1).weight.g, 1.0);
  // The diffuse part of f: ρ (1 − F(wo·h)) / π for wo, wi on either side of the normal.
  Material diffuse_only = material;
  diffuse_only.ks = constant_texture(0.0);
  diffuse_only.layered = false;
  diffuse_only.prepare();
  const Bsdf lambert = bsdf_of(diffuse_only);
  for (const double angle : {0.0, 40.0, 80.0}) {
    const double a = angle * kPi / 180;
    const Vec3 wo{std::sin(a), 0, std::cos(a)}, wi{-std::sin(a / 2), 0, std::cos(a / 2)};
    const Vec3 h = normalize(wo + wi);
    const double fresnel = 0.04 + 0.96 * std::pow(1 - dot(wo, h), 5);
    Bsdf facets_alone(layered.frame(), Vec3{0, 0, 1});
    facets_alone.add(layered.lobe(1));
    const double diffuse = layered.evaluate(wo, wi).g - facets_alone.evaluate(wo, wi).g;
    EXPECT_NEAR(diffuse, lambert.evaluate(wo, wi).g * (1 - fresnel), 1e-12) << angle;
  }
  // A white layered surface reflects about what arrives (the furnace): the mean sample weight over a
  // 64 × 64 grid of (u_lobe, u), from above and from 60°, within 1 % above 1 (glTF's fresnel_mix
  // weighs the diffuse by 1 − F(wo·h) of the one facet that links wo and wi, not of every facet:
  // not exactly complementary, as its specification says) and not far below (GGX's single
  // scattering loses a little).
  Material white = material;
  white.kd = constant_texture(1.0);
  white.prepare();
  const Bsdf furnace = bsdf_of(white);
  for (const double angle : {0.0, 60.0}) {
    const Vec3 wo{std::sin(angle * kPi / 180), 0, std::cos(angle * kPi / 180)};
    double albedo = 0;
    constexpr int kSide = 64;
    for (int i = 0; i < kSide; ++i)
      for (int j = 0; j < kSide; ++j)
        for (const double u_lobe : {0.25, 0.75}) {
          BsdfSample sample;
          if (furnace.sample(wo, u_lobe, {(i + 0.5) / kSide, (j + 0.5) / kSide}, sample))
            albedo += sample.weight.g / (2.0 * kSide * kSide);
        }
    EXPECT_LT(albedo, 1.01) << angle;
    EXPECT_GT(albedo, 0.9) << angle;
  }
  // Without the flag the energy rule divides both lobes by kd + ks.
  material.layered = false;
  material.prepare();
  EXPECT_NEAR(bsdf_of(material).lobe(0).weight.g, 0.8 / 1.8, 1e-12);
}

TEST(MaterialBsdf, DefaultMaterialIsLambert) {
  const Bsdf bsdf = bsdf_of(Material());
  ASSERT_EQ(bsdf.lobe_count(), 1);
  EXPECT_EQ(bsdf.lobe(0).type, LobeType::lambert);
  EXPECT_EQ(bsdf.lobe(0).weight, Color(0.8));
}

// prepare() keeps at()'s result for a material with nothing textured; a textured one (and one
// prepared again after a texture is replaced) is still evaluated at each point.
TEST(MaterialBsdf, PreparedMaterialsGiveThePropertiesOfEveryPoint) {
  Material material;
  material.kd = constant_texture(Color(0.3, 0.2, 0.1));
  material.ks = constant_texture(0.4);
  material.kr = constant_texture(0.25);
  material.prepare();
  SurfaceHit hit = flat_hit();
  EXPECT_EQ(material.at(hit).kd, Color(0.3, 0.2, 0.1));
  EXPECT_DOUBLE_EQ(material.at(hit).ks, 0.4);
  EXPECT_DOUBLE_EQ(material.at(hit).kr, 0.25);
  material.kd = std::make_shared<CheckerboardTexture>(Color(1, 0, 0), Color(0, 0, 1), 1.0, Vec3{});
  material.prepare();
  hit.object_position = {0.5, 0.5, 0.5};
  const Color here = material.at(hit).kd;
  hit.object_position = {1.5, 0.5, 0.5};
  EXPECT_NE(material.at(hit).kd, here);
  EXPECT_DOUBLE_EQ(material.at(hit).ks, 0.4);
}

TEST(MaterialBsdf, DiffuseAlbedoIsClampedKd) {
  Material material;
  material.kd = constant_texture(Color(1.5, 0.5, 0));
  const Bsdf bsdf = bsdf_of(material);
  ASSERT_EQ(bsdf.lobe_count(), 1);
  EXPECT_EQ(bsdf.lobe(0).weight, Color(1, 0.5, 0));
}

TEST(MaterialBsdf, PhongAndBlinnPhongBecomeTheNormalizedPhongLobe) {
  for (const auto model : {SpecularModel::phong, SpecularModel::blinn_phong}) {
    Material material;
    material.specular_model = model;
    material.kd = constant_texture(Color(0.3, 0.2, 0.1));
    material.ks = constant_texture(0.5);
    material.shininess = constant_texture(40.0);
    const Bsdf bsdf = bsdf_of(material);
    ASSERT_EQ(bsdf.lobe_count(), 2);
    EXPECT_EQ(bsdf.lobe(0).type, LobeType::lambert);
    EXPECT_EQ(bsdf.lobe(0).weight, Color(0.3, 0.2, 0.1));
    EXPECT_EQ(bsdf.lobe(1).type, LobeType::phong);
    EXPECT_EQ(bsdf.lobe(1).weight, Color(0.5));
    EXPECT_EQ(bsdf.lobe(1).exponent, 40.0);
  }
}

TEST(MaterialBsdf, CookTorranceBecomesMicrofacet) {
  Material material;
  material.specular_model = SpecularModel::cook_torrance;
  material.kd = constant_texture(0.2);
  material.ks = constant_texture(0.6);
  material.roughness = constant_texture(0.25);
  material.fresnel = Fresnel::dielectric(Color(1.2, 1.5, 2.0));
  Bsdf bsdf = bsdf_of(material);
  ASSERT_EQ(bsdf.lobe_count(), 2);
  EXPECT_EQ(bsdf.lobe(1).type, LobeType::microfacet);
  EXPECT_EQ(bsdf.lobe(1).weight, Color(0.6));
  EXPECT_EQ(bsdf.lobe(1).alpha, 0.25);
  EXPECT_EQ(bsdf.lobe(1).distribution, MicrofacetDistribution::beckmann);
  EXPECT_TRUE(bsdf.lobe(1).fresnel == Fresnel::dielectric(Color(1.2, 1.5, 2.0)));
  material.microfacet = MicrofacetDistribution::ggx;
  bsdf = bsdf_of(material);
  EXPECT_EQ(bsdf.lobe(1).distribution, MicrofacetDistribution::ggx);
}

TEST(MaterialBsdf, KrIsAMirrorAndKtADielectric) {
  Material material;
  material.kd = constant_texture(0.0);
  material.kr = constant_texture(0.3);
  material.kt = constant_texture(0.6);
  material.ior = constant_texture(1.33);
  material.prepare();
  const Bsdf bsdf = bsdf_of(material);
  ASSERT_EQ(bsdf.lobe_count(), 2);  // the black Lambert lobe is dropped
  EXPECT_EQ(bsdf.lobe(0).type, LobeType::mirror);
  EXPECT_EQ(bsdf.lobe(0).weight, Color(0.3));
  EXPECT_EQ(bsdf.lobe(1).type, LobeType::dielectric);
  EXPECT_EQ(bsdf.lobe(1).weight, Color(0.6));
  EXPECT_EQ(bsdf.lobe(1).ior, 1.33);
  EXPECT_FALSE(bsdf.has_non_delta());
}

TEST(MaterialBsdf, WeightsAboveOneAreScaledDown) {
  Material material;
  material.kd = constant_texture(Color(0.8, 0.4, 0.2));
  material.ks = constant_texture(0.4);
  material.kr = constant_texture(0.2);
  material.prepare();
  const Bsdf bsdf = bsdf_of(material);
  ASSERT_EQ(bsdf.lobe_count(), 3);
  // Red: 0.8 + 0.4 + 0.2 = 1.4 → scaled to 1; green 1.0 and blue 0.8 stay.
  EXPECT_NEAR(bsdf.lobe(0).weight.r, 0.8 / 1.4, 1e-15);
  EXPECT_NEAR(bsdf.lobe(1).weight.r, 0.4 / 1.4, 1e-15);
  EXPECT_NEAR(bsdf.lobe(2).weight.r, 0.2 / 1.4, 1e-15);
  EXPECT_NEAR(bsdf.lobe(0).weight.g, 0.4, 1e-15);
  EXPECT_NEAR(bsdf.lobe(1).weight.b, 0.4, 1e-15);
}

TEST(MaterialBsdf, ShadingNormalIsTurnedToTheGeometricSide) {
  const Vec3 tilted = normalize(Vec3{0.2, 0, -1});  // a shading normal given on the back side
  const Bsdf bsdf = bsdf_of(Material(), tilted);
  EXPECT_GT(dot(bsdf.frame().n, bsdf.geometric_normal()), 0);
  EXPECT_NEAR(bsdf.frame().n.x, -tilted.x, 1e-15);
  EXPECT_NEAR(length(bsdf.frame().s), 1, 1e-12);
  EXPECT_NEAR(dot(bsdf.frame().s, bsdf.frame().n), 0, 1e-12);
  EXPECT_NEAR(dot(bsdf.frame().t, bsdf.frame().n), 0, 1e-12);
  EXPECT_NEAR(dot(bsdf.frame().s, bsdf.frame().t), 0, 1e-12);
}

}  // namespace
}  // namespace candela
