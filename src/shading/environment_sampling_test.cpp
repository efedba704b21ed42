// Importance sampling of environment maps (SPEC §12): E[radiance/pdf] over samples equals the
// radiance integrated over the sphere by dense quadrature; sample's pdf is pdf(direction) bit
// for bit; pdf integrates to 1; the density is higher toward a bright texel; black maps sample
// nothing.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <memory>
#include <vector>

#include "math/constants.h"
#include "math/pcg32.h"
#include "sampling/sphere_quadrature.h"
#include "shading/environment.h"

namespace candela {
namespace {

// A w × h image: a dim color gradient with one bright texel at (bright_x, bright_y) (from the
// bottom row).
std::shared_ptr<const TextureImage> test_image(int w, int h, int bright_x, int bright_y, double seed) {
  std::vector<float> rgb;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const bool bright = x == bright_x && y == bright_y;
      const double base = 0.05 + 0.1 * std::fabs(std::sin(seed + 0.7 * x + 1.3 * y));
      rgb.push_back(static_cast<float>(bright ? 40.0 : base));
      rgb.push_back(static_cast<float>(bright ? 30.0 : base * 0.5));
      rgb.push_back(static_cast<float>(bright ? 10.0 : base * 2 * (x % 2)));  // some texels blue-free
    }
  return std::make_shared<const TextureImage>(w, h, std::move(rgb));
}

void check_environment(const Environment& environment, double quadrature_tolerance, uint64_t seed) {
  SCOPED_TRACE(std::string(environment.type_name()));
  // The reference: ∫ L dω (luminance) and ∫ pdf dω by quadrature.
  const double integral =
      integrate_over_sphere([&](const Vec3& d) { return luminance(environment.radiance(d)); }, 800, 1600);
  const double pdf_integral =
      integrate_over_sphere([&](const Vec3& d) { return environment.pdf(d); }, 800, 1600);
  EXPECT_NEAR(pdf_integral, 1, quadrature_tolerance);

  Pcg32 rng(seed, 11);
  double sum = 0, sum_squares = 0;
  const int n = 40000;
  for (int i = 0; i < n; ++i) {
    Vec3 direction;
    double pdf = 0;
    Color radiance;
    ASSERT_TRUE(environment.sample({rng.next_double(), rng.next_double()}, direction, pdf, radiance));
    EXPECT_NEAR(length(direction), 1, 1e-12);
    EXPECT_EQ(pdf, environment.pdf(direction));
    EXPECT_EQ(radiance, environment.radiance(direction));
    ASSERT_GT(pdf, 0);
    const double value = luminance(radiance) / pdf;
    sum += value;
    sum_squares += value * value;
  }
  const double mean = sum / n;
  const double error = std::sqrt(std::max(0.0, sum_squares / n - mean * mean) / n);
  EXPECT_NEAR(mean, integral, 4 * error + quadrature_tolerance * integral);
  // Importance sampling pays: the relative error is far below uniform sampling's.
  EXPECT_LT(error / mean, 0.01);
}

TEST(EnvironmentSampling, ConstantIsUniformAndBlackSamplesNothing) {
  const ConstantEnvironment environment(Color(0.2, 0.5, 1));
  check_environment(environment, 1e-9, 1);
  EXPECT_DOUBLE_EQ(environment.pdf({0, 0, 1}), 1 / (4 * kPi));
  const ConstantEnvironment black(Color(0));
  Vec3 d;
  double pdf;
  Color radiance;
  EXPECT_FALSE(black.sample({0.5, 0.5}, d, pdf, radiance));
  EXPECT_EQ(black.pdf({0, 0, 1}), 0);
}

TEST(EnvironmentSampling, Equirectangular) {
  EquirectangularEnvironment environment(test_image(16, 8, 5, 6, 0.3), {0, 1, 0.2}, {1, 0, 0.3},
                                         Color(1, 0.8, 1.2));
  Vec3 d;
  double pdf;
  Color radiance;
  EXPECT_FALSE(environment.sample({0.5, 0.5}, d, pdf, radiance));  // not prepared yet
  environment.prepare_sampling();
  check_environment(environment, 2e-3, 2);
  // The bright texel (column 5, row 6 from the bottom: v from the top = 1.5/8) is far denser
  // than a dim one with the same sin θ (v = 1.5/8 too, column 12).
  const auto direction_at = [&](double u, double v) {
    const double theta = kPi * v, phi = 2 * kPi * (u - 0.5);
    Vec3 up = normalize(Vec3{0, 1, 0.2});
    Vec3 forward = Vec3{1, 0, 0.3} - up * dot(Vec3{1, 0, 0.3}, up);
    forward = normalize(forward);
    const Vec3 right = cross(forward, up);
    return forward * (std::sin(theta) * std::cos(phi)) + right * (std::sin(theta) * std::sin(phi)) +
           up * std::cos(theta);
  };
  const Vec2 check = environment.panorama_coordinates(direction_at(5.5 / 16, 1.5 / 8));
  EXPECT_NEAR(check.x, 5.5 / 16, 1e-12);
  EXPECT_NEAR(check.y, 1.5 / 8, 1e-12);
  EXPECT_GT(environment.pdf(direction_at(5.5 / 16, 1.5 / 8)),
            50 * environment.pdf(direction_at(12.5 / 16, 1.5 / 8)));
  // Black: nothing to sample.
  EquirectangularEnvironment black(test_image(4, 2, 0, 0, 0), {0, 0, 1}, {1, 0, 0}, Color(0));
  black.prepare_sampling();
  EXPECT_FALSE(black.sample({0.5, 0.5}, d, pdf, radiance));
  EXPECT_EQ(black.pdf({1, 0, 0}), 0);
}

TEST(EnvironmentSampling, CubeMapBothLayouts) {
  for (const CubeLayout layout : {CubeLayout::inside, CubeLayout::opengl}) {
    std::array<std::shared_ptr<const TextureImage>, 6> faces;
    for (int face = 0; face < 6; ++face) faces[face] = test_image(6, 6, face == 4 ? 1 : -1, 4, face);
    CubeMapEnvironment environment(faces, Color(1, 1, 0.7), layout);
    environment.prepare_sampling();
    // The radiance does not blend across faces: the quadrature is first order at the edges.
    check_environment(environment, 3e-3, 3 + static_cast<int>(layout));
    // The bright texel: face +z, column 1, row 4 from the bottom, i.e. t from the top in
    // [1/6, 2/6] and image column 1 (s = 1.5/6 for opengl, 1 − 1.5/6 inside).
    const double s = layout == CubeLayout::opengl ? 1.5 / 6 : 1 - 1.5 / 6, t = 1.5 / 6;
    const Vec3 bright{2 * s - 1, -(2 * t - 1), 1};  // +z: sc = rx, tc = −ry
    const auto at = CubeMapEnvironment::face_coordinates(bright);
    EXPECT_EQ(at.face, CubeMapEnvironment::positive_z);
    EXPECT_NEAR(at.s, s, 1e-12);
    EXPECT_GT(environment.radiance(normalize(bright)).r, 30);
    const Vec3 dim{-(2 * s - 1), -(2 * t - 1), 1};
    EXPECT_GT(environment.pdf(normalize(bright)), 50 * environment.pdf(normalize(dim)));
  }
}

}  // namespace
}  // namespace candela
