#include "shading/optics.h"

#include <gtest/gtest.h>

#include <cmath>

#include "math/constants.h"
#include "shading/local_model.h"

namespace candela {
namespace {

TEST(Optics, ReflectionMirrorsAboutTheNormal) {
  // 000 eq. 5-5 with V at 45° in the xy plane.
  const Vec3 N{0, 1, 0};
  const Vec3 V = normalize(Vec3{-1, 1, 0});
  const Vec3 R = reflect(V, N);
  EXPECT_NEAR(R.x, std::sqrt(0.5), 1e-15);
  EXPECT_NEAR(R.y, std::sqrt(0.5), 1e-15);
  EXPECT_NEAR(R.z, 0, 1e-15);
  EXPECT_NEAR(dot(R, N), dot(V, N), 1e-15);  // equal angles
}

TEST(Optics, RefractionObeysSnellsLaw) {
  const Vec3 N{0, 1, 0};
  for (double incident_degrees : {0.0, 10.0, 30.0, 60.0, 85.0}) {
    const double theta = incident_degrees * kPi / 180;
    const Vec3 V{-std::sin(theta), std::cos(theta), 0};  // toward the viewer, above the surface
    const double eta1 = 1.0, eta2 = 1.5;
    Vec3 T;
    ASSERT_TRUE(refract(V, N, eta1 / eta2, T));
    EXPECT_NEAR(length(T), 1.0, 1e-12);
    EXPECT_LT(T.y, 0);  // into the material
    const double sin_transmitted = std::sqrt(T.x * T.x + T.z * T.z);
    EXPECT_NEAR(eta1 * std::sin(theta), eta2 * sin_transmitted, 1e-12);
    EXPECT_GE(T.x, 0);  // continues forward, in the plane of V and N
    EXPECT_NEAR(T.z, 0, 1e-15);
  }
}

TEST(Optics, TotalInternalReflectionBeyondTheCriticalAngle) {
  const Vec3 N{0, 1, 0};
  const double eta = 1.5;  // glass to air
  const double critical = std::asin(1 / eta);
  Vec3 T;
  const double below = critical - 1e-6, above = critical + 1e-6;
  EXPECT_TRUE(refract({-std::sin(below), std::cos(below), 0}, N, eta, T));
  EXPECT_FALSE(refract({-std::sin(above), std::cos(above), 0}, N, eta, T));
}

TEST(LocalModel, LambertAndPhongTerms) {
  Material material;
  SurfaceProperties at;
  at.ks = 0.5;
  at.shininess = 10;
  at.kd = Color(0.4, 0.5, 0.6);
  const Vec3 N{0, 0, 1};
  const Vec3 L = normalize(Vec3{1, 0, 1});
  const Vec3 V = normalize(Vec3{-1, 0, 1});  // exactly along R: (R·V)^n = 1
  const Color I = direct_term(material, at, N, V, L, Color(2));
  const double n_dot_l = std::sqrt(0.5);
  EXPECT_NEAR(I.r, 2 * (0.4 * n_dot_l + 0.5), 1e-12);
  EXPECT_NEAR(I.b, 2 * (0.6 * n_dot_l + 0.5), 1e-12);
  // Blinn-Phong: H = N here, so (N·H)^n = 1 too.
  material.specular_model = SpecularModel::blinn_phong;
  EXPECT_NEAR(direct_term(material, at, N, V, L, Color(2)).g, 2 * (0.5 * n_dot_l + 0.5), 1e-12);
  // Off the mirror direction by 30° the Phong lobe is cos^10(30°).
  material.specular_model = SpecularModel::phong;
  const Vec3 V2 = normalize(Vec3{-std::sin(kPi / 4 - kPi / 6), 0, std::cos(kPi / 4 - kPi / 6)});
  EXPECT_NEAR(direct_term(material, at, N, V2, L, Color(1)).r,
              0.4 * n_dot_l + 0.5 * std::pow(std::cos(kPi / 6), 10), 1e-12);
}

TEST(LocalModel, NoContributionFromBehind) {
  Material material;
  SurfaceProperties at;
  at.ks = 1;
  at.kd = Color(1);
  const Color I = direct_term(material, at, {0, 0, 1}, {0, 0, 1}, normalize(Vec3{1, 0, -1}), Color(1));
  EXPECT_TRUE(I.is_black());
}

}  // namespace
}  // namespace candela
