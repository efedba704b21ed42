// Bump mapping (000 §4.2.1): the perturbed normal is the normal of q' = q + f·n.
#include "shading/bump.h"

#include <gtest/gtest.h>

#include <cmath>

#include "math/constants.h"
#include "shading/image_texture.h"
#include "shading/noise.h"
#include "shading/procedural_textures.h"

namespace candela {
namespace {

// A height that is a linear function of the object position: f = dot(gradient, p).
class LinearSolidHeight final : public SolidTexture {
 public:
  explicit LinearSolidHeight(const Vec3& gradient) : gradient_(gradient) {}
  Color at(const Vec3& p) const override { return Color(dot(gradient_, p)); }
  std::string_view type_name() const override { return "linear"; }

 private:
  Vec3 gradient_;
};

SurfaceHit plane_hit(double u, double v) {
  SurfaceHit hit;
  hit.uv = {u, v};
  hit.position = hit.object_position = {u, v, 0};
  hit.geometric_normal = hit.shading_normal = {0, 0, 1};
  hit.dpdu = {1, 0, 0};
  hit.dpdv = {0, 1, 0};
  return hit;
}

TEST(Bump, SineWavesOnAPlaneGiveTheAnalyticNormal) {
  // q'(u, v) = (u, v, s·A sin(2πku)): ∂q'/∂u = (1, 0, s·A·2πk cos(2πku)), ∂q'/∂v = (0, 1, 0),
  // normal ∝ (−s·A·2πk cos(2πku), 0, 1).
  const double amplitude = 0.5, k = 3, scale = 0.1;
  BumpMap bump;
  bump.height = std::make_shared<WavesTexture>(std::vector<Wave>{{amplitude, {k, 0}, 0}},
                                               std::make_shared<ParametricMapping>());
  bump.scale = scale;
  for (const double u : {0.0, 0.05, 0.13, 0.4, 0.77}) {
    const Vec3 n = bumped_normal(bump, plane_hit(u, 0.3));
    const Vec3 expected = normalize(Vec3{-scale * amplitude * 2 * kPi * k * std::cos(2 * kPi * k * u), 0, 1});
    // Central differences with δ = 1e-4: relative error δ²(2πk)²/6 ≈ 6e-7.
    EXPECT_NEAR(n.x, expected.x, 2e-6) << u;
    EXPECT_NEAR(n.y, 0.0, 1e-12) << u;
    EXPECT_NEAR(n.z, expected.z, 2e-6) << u;
  }
}

TEST(Bump, HeightImageSlopeBetweenTexelCentres) {
  // Texels 0, 1, 2 along u (centres at u = 1/6, 1/2, 5/6): bilinear slope 1 per 1/3 of u, so
  // f_u = scale·3 anywhere strictly between the first and last centres.
  auto image = std::make_shared<const TextureImage>(3, 1, std::vector<float>{0, 0, 0, 1, 1, 1, 2, 2, 2});
  BumpMap bump;
  bump.height =
      std::make_shared<ImageTexture>(image, WrapMode::clamp, Color(1), std::make_shared<ParametricMapping>());
  bump.scale = 0.2;
  for (const double u : {0.25, 0.4, 0.6, 0.75}) {
    const Vec3 n = bumped_normal(bump, plane_hit(u, 0.5));
    const Vec3 expected = normalize(Vec3{-0.2 * 3, 0, 1});
    EXPECT_NEAR(n.x, expected.x, 1e-9) << u;
    EXPECT_NEAR(n.z, expected.z, 1e-9) << u;
  }
  // Beyond the last centre the clamped image is flat.
  EXPECT_NEAR(bumped_normal(bump, plane_hit(0.95, 0.5)).z, 1.0, 1e-12);
}

TEST(Bump, NoiseHeightTiltsTheNormalAlongItsGradient) {
  // fbm with one octave: f = 0.5 + 0.5·noise(p), so f_u = 0.5·∇noise·dpdu on the plane z = 0.
  NoiseParameters parameters;
  parameters.octaves = 1;
  BumpMap bump;
  bump.height = std::make_shared<NoiseTexture>(parameters);
  bump.scale = 0.3;
  for (const Vec2 at : {Vec2{0.3, 0.7}, Vec2{1.45, -2.2}, Vec2{5.1, 3.9}}) {
    const Vec3 gradient = gradient_noise_gradient({at.x, at.y, 0});
    const Vec3 expected = normalize(Vec3{-0.3 * 0.5 * gradient.x, -0.3 * 0.5 * gradient.y, 1});
    const Vec3 n = bumped_normal(bump, plane_hit(at.x, at.y));
    EXPECT_NEAR(n.x, expected.x, 1e-6);
    EXPECT_NEAR(n.y, expected.y, 1e-6);
    EXPECT_NEAR(n.z, expected.z, 1e-6);
  }
}

TEST(Bump, SolidHeightsFollowTheObjectSpaceDerivatives) {
  // f = 2·x_object. The hit's object dpdu is (0.5, 0, 0) (the object is scaled ×2 in the world),
  // so f_u = 2·0.5 = 1 and the normal tilts to (−1, 0, 1)/√2 with world dpdu = (1, 0, 0).
  BumpMap bump;
  bump.height = std::make_shared<LinearSolidHeight>(Vec3{2, 0, 0});
  SurfaceHit hit = plane_hit(0.2, 0.2);
  hit.transformed = true;
  hit.object_dpdu_ = {0.5, 0, 0};
  hit.object_dpdv_ = {0, 0.5, 0};
  const Vec3 n = bumped_normal(bump, hit);
  EXPECT_NEAR(n.x, -std::sqrt(0.5), 1e-9);
  EXPECT_NEAR(n.z, std::sqrt(0.5), 1e-9);
}

TEST(Bump, KeepsTheShadingNormalsSide) {
  // A surface whose dpdu × dpdv points against its normal (a lower box face) still gets a
  // normal on the same side, tilted the same way as q' = q + f·n demands.
  BumpMap bump;
  bump.height = std::make_shared<LinearSolidHeight>(Vec3{1, 0, 0});
  SurfaceHit hit = plane_hit(0, 0);
  hit.dpdv = {0, -1, 0};  // dpdu × dpdv = −z
  const Vec3 n = bumped_normal(bump, hit);
  EXPECT_GT(n.z, 0);
  // f increases along +x: the displaced surface rises toward +x, its normal leans to −x.
  EXPECT_NEAR(n.x, -std::sqrt(0.5), 1e-9);
}

TEST(Bump, FlatHeightKeepsAnInterpolatedNormal) {
  // A smooth mesh's shading normal differs from dpdu × dpdv; a zero slope must leave it as is.
  BumpMap bump;
  bump.height = std::make_shared<LinearSolidHeight>(Vec3{0, 0, 0});
  SurfaceHit hit = plane_hit(0.3, 0.3);
  hit.shading_normal = normalize(Vec3{0.2, -0.1, 1});
  const Vec3 n = bumped_normal(bump, hit);
  EXPECT_NEAR(n.x, hit.shading_normal.x, 1e-15);
  EXPECT_NEAR(n.y, hit.shading_normal.y, 1e-15);
  EXPECT_NEAR(n.z, hit.shading_normal.z, 1e-15);
}

TEST(Bump, NoHeightOrNoTangentPlaneLeavesTheNormal) {
  const SurfaceHit hit = plane_hit(0.5, 0.5);
  EXPECT_EQ(bumped_normal(BumpMap{}, hit), hit.shading_normal);
  BumpMap bump;
  bump.height = std::make_shared<LinearSolidHeight>(Vec3{1, 1, 1});
  SurfaceHit pole = hit;
  pole.dpdu = {0, 0, 0};  // the pole of a sphere
  EXPECT_EQ(bumped_normal(bump, pole), hit.shading_normal);
  // A flat height changes nothing.
  bump.height = std::make_shared<LinearSolidHeight>(Vec3{0, 0, 0});
  const Vec3 n = bumped_normal(bump, hit);
  EXPECT_NEAR(n.z, 1.0, 1e-15);
}

}  // namespace
}  // namespace candela
