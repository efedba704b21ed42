// The classic material's parameters as BSDF lobes (material_bsdf.h). The scene key "microfacet"
// is tests/material_scene_test.cpp.
#include "shading/material_bsdf.h"

#include <gtest/gtest.h>

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
