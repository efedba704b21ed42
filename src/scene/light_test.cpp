#include <gtest/gtest.h>

#include <cmath>

#include "geometry/quad.h"
#include "geometry/sphere.h"
#include "math/constants.h"
#include "sampling/sphere_quadrature.h"
#include "scene/area_light.h"
#include "scene/directional_light.h"
#include "scene/environment_light.h"
#include "scene/point_light.h"
#include "scene/spot_light.h"
#include "scene/surface_light.h"
#include "shading/environment.h"

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

// The luminance of the power that crosses the sphere of `radius` about the origin: the irradiance
// of every sample of the light (Σ intensity · cos θ, the lights' own convention) integrated over
// the sphere (r² dω). A light inside lights the sphere's inner faces; a light from outside
// (`from_outside`) the outer ones, the flux that enters.
double flux_through_sphere(const Light& light, double radius, bool from_outside) {
  const auto irradiance = [&](const Vec3& outward) {
    const Vec3 facing = from_outside ? outward : -outward;
    double sum = 0;
    for (int k = 0; k < light.sample_count(); ++k) {
      LightSample sample;
      if (!light.illuminate_sample(outward * radius, k, {0.5, 0.5}, sample)) continue;
      sum += luminance(sample.intensity) * std::max(0.0, dot(facing, sample.direction));
    }
    return sum;
  };
  return radius * radius * integrate_over_sphere(irradiance, 300, 600);
}

// One emitter model: Light::power is the power each light sends — measured here as what
// crosses a sphere around it, from the lights' own illumination — the measure the path tracer
// chooses lights by (for the lights that fall off slower than 1/d², what reaches the sphere of the
// scene's radius).
TEST(Lights, PowerIsWhatCrossesASphereAroundTheLight) {
  const double r = 5;
  Attenuation linear;
  linear.mode = Attenuation::Mode::linear;
  linear.d0 = 1;
  const PointLight point({0, 0, 0}, Color(3), linear);
  EXPECT_NEAR(flux_through_sphere(point, r, false) / luminance(point.power(r)), 1, 1e-6);
  EXPECT_NEAR(luminance(point.power(r)), 3 * 4 * kPi * r * r / (r + 1), 1e-9);
  Attenuation inverse_square;
  inverse_square.mode = Attenuation::Mode::inverse_square;
  EXPECT_NEAR(luminance(PointLight({0, 0, 0}, Color(3), inverse_square).power(r)), 3, 1e-12);
  // The smooth step between 20° and 30° sends half of what the full cone between would.
  const SpotLight spot({0, 0, 0}, {0, -1, 0.2}, Color(2), 30, 20, 0, Attenuation{});
  EXPECT_NEAR(flux_through_sphere(spot, r, false) / luminance(spot.power(r)), 1, 2e-3);
  const DirectionalLight sun({1, -2, 0.5}, Color(0.7));
  EXPECT_NEAR(flux_through_sphere(sun, r, true) / luminance(sun.power(r)), 1, 1e-3);
  for (const bool two_sided : {false, true}) {
    const AreaLight area({-0.5, 1, -0.25}, {1, 0, 0}, {0, 0.2, 0.5}, Color(4), 6, two_sided);
    EXPECT_NEAR(flux_through_sphere(area, r, false) / luminance(area.power(r)), 1, 2e-3) << two_sided;
    EXPECT_NEAR(luminance(area.power(r)), 4 * area.area() * (two_sided ? 2 : 1), 1e-12);
    EXPECT_EQ(area.emitted_radiance({0, 1, 0}), Color());  // no ray sees it
  }
  // An emissive surface sends its exitance from both sides: two quads of one object.
  const Quad quad({-1, -1, 0}, {2, 0, 0}, {0, 1.5, 0});
  const Quad tilted({0.5, 1, 1}, {0, 0.5, 0.5}, {0.8, 0, 0});
  const SurfaceLight surface("lamp", {&quad, &tilted}, Color(1.5), 8);
  EXPECT_NEAR(luminance(surface.power(r)), 1.5 * 2 * (3 + 0.8 * std::sqrt(0.5)), 1e-12);
  EXPECT_NEAR(flux_through_sphere(surface, r, false) / luminance(surface.power(r)), 1, 3e-3);
  EXPECT_EQ(surface.emitted_radiance({0, 0, 1}), Color(1.5));
  // A uniform sky of color C: irradiance C on every element of the sphere, 4π r² C in all.
  ConstantEnvironment sky_color(Color(0.8, 0.6, 0.4));
  const EnvironmentLight sky(sky_color, 8);
  EXPECT_NEAR(sky.mean_radiance().g, 0.6, 1e-12);
  EXPECT_NEAR(flux_through_sphere(sky, r, true) / luminance(sky.power(r)), 1, 2e-3);
  EXPECT_EQ(sky.emitted_radiance({0, 1, 0}), Color(0.8, 0.6, 0.4));
}

// The random sample of an emitter a ray can hit gives the density of its direction (for MIS):
// Σ intensity·cos / pdf-weighted estimates agree with the stratified set, and pdf is the emitter's
// own density (the sphere's cone, the quad's area measure).
TEST(Lights, RandomSamplesOfSurfacesAndTheSkyCarryTheirDensity) {
  const Sphere ball({0, 3, 0}, 1);
  const SurfaceLight surface("ball", {&ball}, Color(2), 4);
  LightSample sample;
  ASSERT_TRUE(surface.illuminate_random({0, 0, 0}, {0.3, 0.6}, sample));
  // Uniform in the cone of half-angle asin(1/3): pdf = 1 / (2π (1 − cos θmax)).
  const double cos_max = std::sqrt(1 - 1.0 / 9);
  EXPECT_NEAR(sample.pdf, 1 / (2 * kPi * (1 - cos_max)), 1e-9);
  EXPECT_NEAR(sample.intensity.r, 2 * kInvPi / sample.pdf, 1e-9);
  EXPECT_NEAR(length(sample.normal), 1, 1e-12);
  EXPECT_LT(dot(sample.normal, sample.direction), 0);  // it faces the point
  ConstantEnvironment white(Color(1));
  const EnvironmentLight sky(white, 2);
  ASSERT_TRUE(sky.illuminate_random({0, 0, 0}, {0.3, 0.6}, sample));
  EXPECT_NEAR(sample.pdf, 1 / (4 * kPi), 1e-12);
  EXPECT_EQ(sample.normal, Vec3{});
  const PointLight point({0, 3, 0}, Color(1), Attenuation{});
  ASSERT_TRUE(point.illuminate_random({0, 0, 0}, {0.3, 0.6}, sample));
  EXPECT_EQ(sample.pdf, 0);  // no ray can hit it
}

// illuminate_cell hashes the sample's place in its cell only for the lights that say they read it
// (stratified()): every light whose samples move with `within` must say so, or it would lose its
// jitter; the point-like ones, handed the centre instead, give the same sample either way.
TEST(Lights, OnlyTheStratifiedLightsReadWhereInTheCellTheSampleIs) {
  const PointLight point({0, 3, 0}, Color(1), Attenuation{});
  const SpotLight spot({0, 3, 0}, {0, -1, 0}, Color(2), 40, 30, 0, Attenuation{});
  const DirectionalLight sun({1, -2, 0.5}, Color(0.7));
  const DirectionalLight sun_disc({1, -2, 0.5}, Color(0.7), "sun", 0.02, 2);  // an angular diameter
  const AreaLight area({-0.5, 3, -0.25}, {1, 0, 0}, {0, 0, 0.5}, Color(4), 2, true);
  const Quad quad({-1, 3, -1}, {2, 0, 0}, {0, 0, 1.5});
  const SurfaceLight surface("lamp", {&quad}, Color(1.5), 2);
  ConstantEnvironment sky_color(Color(0.8, 0.6, 0.4));
  const EnvironmentLight sky(sky_color, 2);
  const Light* lights[] = {&point, &spot, &sun, &sun_disc, &area, &surface, &sky};
  const Vec3 at{0.1, 0, 0.2};
  for (const Light* light : lights) {
    bool moves = false;
    for (int index = 0; index < light->sample_count(); ++index) {
      LightSample low, high;
      const bool lit_low = light->illuminate_sample(at, index, {0.1, 0.2}, low);
      const bool lit_high = light->illuminate_sample(at, index, {0.9, 0.7}, high);
      moves =
          moves || lit_low != lit_high || low.direction != high.direction || low.distance != high.distance;
    }
    EXPECT_EQ(moves, light->stratified()) << light->type_name();
  }
}

}  // namespace
}  // namespace candela
