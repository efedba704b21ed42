#include <gtest/gtest.h>

#include <cmath>

#include "math/constants.h"
#include "scene/directional_light.h"
#include "scene/point_light.h"
#include "scene/spot_light.h"

namespace candela {
namespace {

TEST(Lights, PointLightDirectionDistanceAndAttenuation) {
  Attenuation attenuation;
  attenuation.mode = Attenuation::Mode::linear;
  attenuation.d0 = 1;
  const PointLight light({0, 4, 3}, Color(10), attenuation);
  LightSample sample;
  ASSERT_TRUE(light.illuminate({0, 0, 0}, sample));
  EXPECT_DOUBLE_EQ(sample.distance, 5);
  EXPECT_NEAR(sample.direction.y, 0.8, 1e-15);
  EXPECT_NEAR(sample.intensity.r, 10.0 / 6, 1e-14);
}

TEST(Lights, DirectionalLightIsTheSameEverywhere) {
  const DirectionalLight light({0, -2, 0}, Color(0.5));
  LightSample a, b;
  ASSERT_TRUE(light.illuminate({0, 0, 0}, a));
  ASSERT_TRUE(light.illuminate({100, -7, 3}, b));
  EXPECT_EQ(a.direction, (Vec3{0, 1, 0}));
  EXPECT_EQ(a.direction, b.direction);
  EXPECT_TRUE(std::isinf(a.distance));
  EXPECT_EQ(b.intensity, Color(0.5));
}

TEST(Lights, SpotConeFullInsideSmoothBetweenZeroOutside) {
  const SpotLight light({0, 10, 0}, {0, 0, 0}, Color(1), 30, 20, 0, Attenuation{});
  EXPECT_DOUBLE_EQ(light.cone_factor(std::cos(degrees_to_radians(10))), 1.0);
  EXPECT_DOUBLE_EQ(light.cone_factor(std::cos(degrees_to_radians(31))), 0.0);
  // Half way in cos between the two edges the smooth step gives exactly 0.5.
  const double c20 = std::cos(degrees_to_radians(20)), c30 = std::cos(degrees_to_radians(30));
  EXPECT_NEAR(light.cone_factor((c20 + c30) / 2), 0.5, 1e-12);
  LightSample sample;
  EXPECT_TRUE(light.illuminate({0, 0, 0}, sample));
  EXPECT_FALSE(light.illuminate({10, 0, 0}, sample));  // 45° off the axis
  // Warn's exponent: cos^e of the angle inside the full cone.
  const SpotLight warn({0, 10, 0}, {0, 0, 0}, Color(1), 60, 60, 3, Attenuation{});
  EXPECT_NEAR(warn.cone_factor(0.9), std::pow(0.9, 3), 1e-12);
}

TEST(Lights, AttenuationFactors) {
  Attenuation a;
  EXPECT_EQ(a.factor(7), 1.0);
  a.mode = Attenuation::Mode::inverse_square;
  EXPECT_NEAR(a.factor(2), 1 / (16 * kPi), 1e-15);
  a.mode = Attenuation::Mode::polynomial;
  a.constant = 0.5;
  a.linear_coefficient = 0.25;
  a.quadratic = 0.125;
  EXPECT_NEAR(a.factor(4), 1 / (0.5 + 1 + 2), 1e-15);
  EXPECT_EQ(a.factor(0), 1.0);  // 1/0.5 clamped to 1
}

}  // namespace
}  // namespace candela
