#include "shading/procedural_textures.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>

#include "math/constants.h"
#include "math/pcg32.h"
#include "shading/checkerboard_texture.h"
#include "shading/noise.h"
#include "shape_test_support.h"

namespace candela {
namespace {

const Color kBlack{0, 0, 0};
const Color kWhite{1, 1, 1};

SurfaceHit hit_at_uv(double u, double v) {
  SurfaceHit hit;
  hit.uv = {u, v};
  return hit;
}

SurfaceHit hit_at_object(const Vec3& p) {
  SurfaceHit hit;
  hit.position = p;
  hit.object_position = p;
  return hit;
}

std::shared_ptr<const TextureMapping> uv_mapping(const UvTransform& uv = {}) {
  return std::make_shared<ParametricMapping>(uv);
}

// Each channel of c lies between the same channels of a and b.
void expect_between(const Color& c, const Color& a, const Color& b) {
  for (int channel = 0; channel < 3; ++channel) {
    EXPECT_GE(c[channel], std::min(a[channel], b[channel]) - 1e-12);
    EXPECT_LE(c[channel], std::max(a[channel], b[channel]) + 1e-12);
  }
}

void expect_near(const Color& a, const Color& b, double tolerance) {
  EXPECT_NEAR(a.r, b.r, tolerance);
  EXPECT_NEAR(a.g, b.g, tolerance);
  EXPECT_NEAR(a.b, b.b, tolerance);
}

// --- 2D checkerboard ---------------------------------------------------------------------------

TEST(Checker2D, CellsAlternateWithUnitSize) {
  const Checkerboard2DTexture checker(kWhite, kBlack, uv_mapping());
  EXPECT_EQ(checker.type_name(), "checker2d");
  EXPECT_EQ(checker.evaluate(hit_at_uv(0.5, 0.5)), kWhite);
  EXPECT_EQ(checker.evaluate(hit_at_uv(1.5, 0.5)), kBlack);
  EXPECT_EQ(checker.evaluate(hit_at_uv(0.5, 1.5)), kBlack);
  EXPECT_EQ(checker.evaluate(hit_at_uv(1.5, 1.5)), kWhite);
  EXPECT_EQ(checker.evaluate(hit_at_uv(-0.5, 0.5)), kBlack);  // floor(−0.5) = −1
  EXPECT_EQ(checker.evaluate(hit_at_uv(-0.5, -0.5)), kWhite);
  EXPECT_EQ(checker.evaluate(hit_at_uv(-2.5, 6.5)), kBlack);  // −3 + 6
  EXPECT_EQ(checker.evaluate(hit_at_uv(-2.5, 7.5)), kWhite);  // −3 + 7
}

TEST(Checker2D, EdgesAndCornersBelongToTheCellAboveAndRight) {
  const Checkerboard2DTexture checker(kWhite, kBlack, uv_mapping());
  EXPECT_EQ(checker.evaluate(hit_at_uv(0, 0)), kWhite);
  EXPECT_EQ(checker.evaluate(hit_at_uv(1, 0)), kBlack);
  EXPECT_EQ(checker.evaluate(hit_at_uv(0, 1)), kBlack);
  EXPECT_EQ(checker.evaluate(hit_at_uv(1, 1)), kWhite);
  EXPECT_EQ(checker.evaluate(hit_at_uv(1, 0.5)), kBlack);
  EXPECT_EQ(checker.evaluate(hit_at_uv(-1, 0)), kBlack);
  EXPECT_EQ(checker.evaluate(hit_at_uv(std::nextafter(1.0, 0.0), 0)), kWhite);
}

TEST(Checker2D, MappingScaleSetsTheNumberOfCells) {
  // 8 × 4 cells over the unit square of the shape's own uv.
  const Checkerboard2DTexture checker(kWhite, kBlack, uv_mapping({{8, 4}, {0, 0}}));
  EXPECT_EQ(checker.evaluate(hit_at_uv(0.01, 0.01)), kWhite);
  EXPECT_EQ(checker.evaluate(hit_at_uv(0.13, 0.01)), kBlack);  // u·8 = 1.04
  EXPECT_EQ(checker.evaluate(hit_at_uv(0.13, 0.26)), kWhite);  // v·4 = 1.04
}

TEST(Checker2D, HugeAndNaNCoordinatesAreSafe) {
  const Checkerboard2DTexture checker(kWhite, kBlack, uv_mapping());
  EXPECT_EQ(checker.evaluate(hit_at_uv(1e9 + 1, 0.5)), kBlack);
  EXPECT_EQ(checker.evaluate(hit_at_uv(-1e9 - 1, 0.5)), kBlack);
  EXPECT_EQ(checker.evaluate(hit_at_uv(1e300, -1e300)), kWhite);  // even integers
  EXPECT_EQ(checker.evaluate(hit_at_uv(std::numeric_limits<double>::quiet_NaN(), 0.5)), kWhite);
  EXPECT_EQ(floor_parity(-1), 1);
  EXPECT_EQ(floor_parity(-0.5), 1);
  EXPECT_EQ(floor_parity(-2), 0);
  EXPECT_EQ(floor_parity(std::numeric_limits<double>::infinity()), 0);
  EXPECT_EQ(floor_parity(0x1p61 + 1024), 0);
  EXPECT_EQ(floor_parity(0x1p52 + 1), 1);
}

TEST(Checker2D, RejectsBadParameters) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(Checkerboard2DTexture(kWhite, kBlack, nullptr), std::invalid_argument);
  EXPECT_THROW(Checkerboard2DTexture(Color(nan), kBlack, uv_mapping()), std::invalid_argument);
}

// --- 3D checkerboard ---------------------------------------------------------------------------

// The checkerboard's formula as it was before it became a SolidTexture.
Color old_checkerboard(const Color& even, const Color& odd, double size, const Vec3& offset,
                       const Vec3& position) {
  const Vec3 p = (position + offset) * (1.0 / size) + Vec3{1e-9, 1e-9, 1e-9};
  const auto cell = static_cast<long long>(std::floor(p.x)) + static_cast<long long>(std::floor(p.y)) +
                    static_cast<long long>(std::floor(p.z));
  return (cell & 1) ? odd : even;
}

TEST(Checkerboard3D, KeepsItsFormerResults) {
  const Vec3 offset{0.25, 0, -3};
  const CheckerboardTexture checker(kWhite, kBlack, 0.7, offset);
  EXPECT_EQ(checker.type_name(), "checkerboard");
  Pcg32 rng(23, 1);
  for (int i = 0; i < 20000; ++i) {
    const Vec3 p = testing::random_point(rng, 25);
    EXPECT_EQ(checker.evaluate(hit_at_object(p)), old_checkerboard(kWhite, kBlack, 0.7, offset, p));
  }
  // Cell faces: the bias puts a floor at y = 0 (and points a hair below it) in the upper cell.
  const CheckerboardTexture unit(kWhite, kBlack, 1, Vec3{});
  EXPECT_EQ(unit.evaluate(hit_at_object({0.5, 0, 0.5})), kWhite);
  EXPECT_EQ(unit.evaluate(hit_at_object({0.5, -1e-12, 0.5})), kWhite);
  EXPECT_EQ(unit.evaluate(hit_at_object({1.5, 0, 0.5})), kBlack);
  EXPECT_EQ(unit.evaluate(hit_at_object({-0.5, 0, 0.5})), kBlack);
  EXPECT_EQ(unit.evaluate(hit_at_object({0.5, -0.5, 0.5})), kBlack);
  EXPECT_EQ(unit.evaluate(hit_at_object({1, 1, 1})), kBlack);
  for (const Vec3& p : {Vec3{0.5, 0, 0.5}, Vec3{1, 1, 1}, Vec3{-2.999999999999, 4, 0}})
    EXPECT_EQ(unit.evaluate(hit_at_object(p)), old_checkerboard(kWhite, kBlack, 1, {}, p));
}

TEST(Checkerboard3D, PlacedByATransform) {
  // Scaling texture space by 2 halves the cells: like size 0.5 without a transform.
  const CheckerboardTexture scaled(kWhite, kBlack, 1, Transform::scale({2, 2, 2}));
  const CheckerboardTexture half(kWhite, kBlack, 0.5, Vec3{});
  // A 90° turn about z swaps x and −y, so the cell at x ∈ [1, 2) lands at y ∈ [1, 2).
  const CheckerboardTexture turned(kWhite, kBlack, 1, Transform::rotate(90, {0, 0, 1}));
  const CheckerboardTexture shifted(kWhite, kBlack, 1, Transform::translate({1, 0, 0}));
  Pcg32 rng(29, 2);
  for (int i = 0; i < 2000; ++i) {
    const Vec3 p = testing::random_point(rng, 10);
    EXPECT_EQ(scaled.evaluate(hit_at_object(p)), half.evaluate(hit_at_object(p)));
    EXPECT_EQ(shifted.evaluate(hit_at_object(p)), old_checkerboard(kWhite, kBlack, 1, {1, 0, 0}, p));
  }
  EXPECT_EQ(turned.evaluate(hit_at_object({0.5, 0.5, 0.5})), kBlack);   // → (−0.5, 0.5, 0.5)
  EXPECT_EQ(turned.evaluate(hit_at_object({0.5, -0.5, 0.5})), kWhite);  // → (0.5, 0.5, 0.5)
}

TEST(Checkerboard3D, RejectsBadParameters) {
  EXPECT_THROW(CheckerboardTexture(kWhite, kBlack, 0, Vec3{}), std::invalid_argument);
  EXPECT_THROW(CheckerboardTexture(kWhite, kBlack, -1, Transform()), std::invalid_argument);
  EXPECT_THROW(CheckerboardTexture(kWhite, kBlack, std::numeric_limits<double>::quiet_NaN(), Vec3{}),
               std::invalid_argument);
}

// --- wood --------------------------------------------------------------------------------------

TEST(ProceduralWood, ColorIsAConvexCombinationOfLightAndDark) {
  const WoodParameters parameters;
  const WoodTexture wood(parameters);
  EXPECT_EQ(wood.type_name(), "wood");
  Pcg32 rng(31, 1);
  double lightest = 1, darkest = 0;
  for (int i = 0; i < 20000; ++i) {
    const Vec3 p = testing::random_point(rng, 3);
    const double d = wood.darkness(p);
    lightest = std::min(lightest, d);
    darkest = std::max(darkest, d);
    EXPECT_GE(d, 0.0);
    EXPECT_LE(d, 1.0);
    const Color c = wood.evaluate(hit_at_object(p));
    expect_between(c, parameters.light, parameters.dark);
    expect_near(c, parameters.light + (parameters.dark - parameters.light) * d, 1e-12);
  }
  // Both the light early wood and the dark late wood occur.
  EXPECT_EQ(lightest, 0.0);
  EXPECT_EQ(darkest, 1.0);
}

TEST(ProceduralWood, RingsArePeriodicInTheRadiusWithoutTurbulence) {
  WoodParameters parameters;
  parameters.ring_frequency = 3;
  parameters.turbulence = 0;
  const WoodTexture wood(parameters);
  const double period = 1.0 / parameters.ring_frequency;
  for (double r = 0.01; r < 2; r += 0.0173) {
    // The same ring value one period further out, and all around the z axis at any height.
    const double d = wood.darkness({r, 0, 0});
    EXPECT_NEAR(wood.darkness({r + period, 0, 0}), d, 1e-9) << r;
    EXPECT_NEAR(wood.darkness({0, r + 2 * period, 5}), d, 1e-9) << r;
    EXPECT_NEAR(wood.darkness({r * std::cos(1.0), r * std::sin(1.0), -2}), d, 1e-9) << r;
  }
  // The profile within a ring: light at its start, dark in the late-wood band.
  EXPECT_EQ(wood.darkness({0.1 * period, 0, 0}), 0.0);
  EXPECT_EQ(wood.darkness({0.9 * period, 0, 0}), 1.0);
}

TEST(ProceduralWood, TurbulenceBendsTheRings) {
  WoodParameters straight;
  straight.turbulence = 0;
  WoodParameters bent;
  bent.turbulence = 0.5;
  const WoodTexture a(straight), b(bent);
  int differing = 0;
  for (double r = 0.05; r < 2; r += 0.05) differing += a.darkness({r, 0.3, 0.2}) != b.darkness({r, 0.3, 0.2});
  EXPECT_GT(differing, 10);
}

TEST(ProceduralWood, RejectsBadParameters) {
  const auto with = [](auto change) {
    WoodParameters parameters;
    change(parameters);
    return parameters;
  };
  EXPECT_THROW(WoodTexture(with([](WoodParameters& p) { p.ring_frequency = 0; })), std::invalid_argument);
  EXPECT_THROW(WoodTexture(with([](WoodParameters& p) { p.turbulence = -1; })), std::invalid_argument);
  EXPECT_THROW(WoodTexture(with([](WoodParameters& p) { p.noise_scale = std::nan(""); })),
               std::invalid_argument);
  EXPECT_THROW(WoodTexture(with([](WoodParameters& p) { p.octaves = 0; })), std::invalid_argument);
  EXPECT_THROW(WoodTexture(with([](WoodParameters& p) { p.octaves = 17; })), std::invalid_argument);
  EXPECT_THROW(WoodTexture(with([](WoodParameters& p) { p.light.g = std::nan(""); })), std::invalid_argument);
}

// --- marble ------------------------------------------------------------------------------------

TEST(ProceduralMarble, ColorIsAConvexCombinationOfBaseAndVein) {
  const MarbleParameters parameters;
  const MarbleTexture marble(parameters);
  EXPECT_EQ(marble.type_name(), "marble");
  Pcg32 rng(37, 1);
  for (int i = 0; i < 20000; ++i) {
    const Vec3 p = testing::random_point(rng, 3);
    const double weight = marble.vein_weight(p);
    EXPECT_GE(weight, 0.0);
    EXPECT_LE(weight, 1.0);
    expect_between(marble.evaluate(hit_at_object(p)), parameters.base, parameters.vein);
  }
}

TEST(ProceduralMarble, WithoutTurbulenceItIsTheSineFormula) {
  MarbleParameters parameters;
  parameters.turbulence = 0;
  parameters.frequency = 5;
  parameters.sharpness = 2.5;
  const MarbleTexture marble(parameters);
  for (double x : {-1.3, 0.0, 0.2, 0.31415926, 0.7, 2.9}) {
    const double value = 0.5 + 0.5 * std::sin(5 * x);
    const Color expected = parameters.base + (parameters.vein - parameters.base) * std::pow(value, 2.5);
    EXPECT_EQ(marble.evaluate(hit_at_object({x, 0.4, -7})), expected) << x;
  }
  // The veins are planes x = const: y and z do not matter.
  EXPECT_EQ(marble.vein_weight({0.3, 0, 0}), marble.vein_weight({0.3, 12, -5}));
}

TEST(ProceduralMarble, TurbulenceEntersThePhase) {
  MarbleParameters parameters;
  parameters.sharpness = 1;
  const MarbleTexture marble(parameters);
  const Vec3 p{0.37, -0.81, 1.22};
  const double phase = parameters.frequency * p.x +
                       parameters.turbulence * turbulence(p * parameters.noise_scale, parameters.octaves);
  EXPECT_NEAR(marble.vein_weight(p), 0.5 + 0.5 * std::sin(phase), 1e-15);
}

TEST(ProceduralMarble, RejectsBadParameters) {
  const auto with = [](auto change) {
    MarbleParameters parameters;
    change(parameters);
    return parameters;
  };
  EXPECT_THROW(MarbleTexture(with([](MarbleParameters& p) { p.frequency = -2; })), std::invalid_argument);
  EXPECT_THROW(MarbleTexture(with([](MarbleParameters& p) { p.sharpness = 0; })), std::invalid_argument);
  EXPECT_THROW(MarbleTexture(with([](MarbleParameters& p) { p.octaves = 20; })), std::invalid_argument);
  EXPECT_THROW(MarbleTexture(with([](MarbleParameters& p) { p.turbulence = std::nan(""); })),
               std::invalid_argument);
}

// --- noise -------------------------------------------------------------------------------------

TEST(ProceduralNoise, FbmIsCentredOnOffsetPlusHalfTheAmplitude) {
  NoiseParameters parameters;
  parameters.amplitude = 2;
  parameters.offset = 0.1;
  const NoiseTexture texture(parameters);
  EXPECT_EQ(texture.type_name(), "noise");
  // Points spread over ~10^6 lattice cells are nearly independent samples. One octave of noise
  // has a standard deviation of about 0.2, so the mean of 40,000 samples of this value
  // (σ ≈ 2·0.5·0.25) has a standard error near 0.0013; the tolerance is about 8 of those.
  Pcg32 rng(41, 1);
  const int count = 40000;
  double sum = 0;
  for (int i = 0; i < count; ++i)
    sum += texture.evaluate_scalar(hit_at_object(testing::random_point(rng, 60)));
  EXPECT_NEAR(sum / count, parameters.offset + parameters.amplitude * 0.5, 0.01);
}

TEST(ProceduralNoise, ValueFollowsTheFormula) {
  NoiseParameters parameters;
  parameters.octaves = 3;
  parameters.lacunarity = 2.5;
  parameters.gain = 0.6;
  parameters.amplitude = 0.8;
  parameters.offset = -0.2;
  parameters.scale = 3;
  const NoiseTexture fbm(parameters);
  parameters.mode = NoiseMode::turbulence;
  const NoiseTexture turb(parameters);
  const Vec3 p{0.13, 0.57, -0.91};
  EXPECT_EQ(fbm.value(p), -0.2 + 0.8 * (0.5 + 0.5 * fractal_noise(p * 3, 3, 2.5, 0.6)));
  EXPECT_EQ(turb.value(p), -0.2 + 0.8 * turbulence(p * 3, 3, 2.5, 0.6));
  EXPECT_EQ(fbm.evaluate(hit_at_object(p)), Color(fbm.value(p)));
}

TEST(ProceduralNoise, TurbulenceModeIsNonNegative) {
  NoiseParameters parameters;
  parameters.mode = NoiseMode::turbulence;
  parameters.octaves = 6;
  const NoiseTexture texture(parameters);
  Pcg32 rng(43, 1);
  double highest = 0;
  for (int i = 0; i < 20000; ++i) {
    const double value = texture.value(testing::random_point(rng, 20));
    EXPECT_GE(value, 0.0);
    highest = std::max(highest, value);
  }
  EXPECT_GT(highest, 0.3);
}

TEST(ProceduralNoise, TransformPlacesTheNoise) {
  const NoiseParameters parameters;
  const NoiseTexture moved(parameters, Transform::translate({10, 0, 0}));
  const NoiseTexture plain(parameters);
  EXPECT_EQ(moved.evaluate(hit_at_object({0.3, 0.4, 0.5})), plain.evaluate(hit_at_object({10.3, 0.4, 0.5})));
}

TEST(ProceduralNoise, RejectsBadParameters) {
  const auto with = [](auto change) {
    NoiseParameters parameters;
    change(parameters);
    return parameters;
  };
  EXPECT_THROW(NoiseTexture(with([](NoiseParameters& p) { p.octaves = 0; })), std::invalid_argument);
  EXPECT_THROW(NoiseTexture(with([](NoiseParameters& p) { p.scale = 0; })), std::invalid_argument);
  EXPECT_THROW(NoiseTexture(with([](NoiseParameters& p) { p.gain = -0.5; })), std::invalid_argument);
  EXPECT_THROW(NoiseTexture(with([](NoiseParameters& p) { p.lacunarity = 0; })), std::invalid_argument);
  EXPECT_THROW(NoiseTexture(with([](NoiseParameters& p) { p.amplitude = std::nan(""); })),
               std::invalid_argument);
}

// --- waves -------------------------------------------------------------------------------------

TEST(ProceduralWaves, IsTheSumOfSines) {
  const std::vector<Wave> waves = {{0.5, {2, 0}, 0}, {0.25, {1, 3}, kPi / 2}, {0.1, {-4, 1}, 1.0}};
  const WavesTexture texture(waves, uv_mapping());
  EXPECT_EQ(texture.type_name(), "waves");
  // At (0, 0): 0.5·sin 0 + 0.25·sin(π/2) + 0.1·sin 1.
  EXPECT_NEAR(texture.value({0, 0}), 0.25 + 0.1 * std::sin(1.0), 1e-15);
  // At (0.125, 0): 0.5·sin(π/2) + 0.25·sin(π/4 + π/2) + 0.1·sin(−π + 1).
  EXPECT_NEAR(texture.value({0.125, 0}), 0.5 + 0.25 * std::sqrt(0.5) + 0.1 * std::sin(1.0 - kPi), 1e-15);
  for (const Vec2 uv : {Vec2{0.3, 0.7}, Vec2{-1.2, 0.05}, Vec2{4.5, -2.25}}) {
    double expected = 0;
    for (const Wave& w : waves)
      expected += w.amplitude * std::sin(2 * kPi * (w.frequency.x * uv.x + w.frequency.y * uv.y) + w.phase);
    EXPECT_NEAR(texture.evaluate(hit_at_uv(uv.x, uv.y)).g, expected, 1e-14);
    EXPECT_NEAR(texture.evaluate_scalar(hit_at_uv(uv.x, uv.y)), expected, 1e-14);
  }
}

TEST(ProceduralWaves, RejectsBadParameters) {
  EXPECT_THROW(WavesTexture({}, uv_mapping()), std::invalid_argument);
  EXPECT_THROW(WavesTexture({{1, {0, 0}, 0}}, uv_mapping()), std::invalid_argument);
  EXPECT_THROW(WavesTexture({{std::nan(""), {1, 0}, 0}}, uv_mapping()), std::invalid_argument);
  EXPECT_THROW(WavesTexture({{1, {1, 0}, 0}}, nullptr), std::invalid_argument);
}

}  // namespace
}  // namespace candela
