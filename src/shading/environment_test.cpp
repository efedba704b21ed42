// Environment maps (000 §4.1.3, SPEC §7): the cube map's face choice and OpenGL (s, t) on
// hand-computed directions and the lat-long panorama's orientation. The registry's JSON forms
// and errors are tests/environment_registry_test.cpp.
#include "shading/environment.h"

#include <gtest/gtest.h>

#include <memory>
#include <stdexcept>
#include <vector>

#include "math/constants.h"
#include "util/error.h"

namespace candela {
namespace {

std::shared_ptr<const TextureImage> constant_image(int width, int height, const Color& color) {
  std::vector<float> rgb;
  for (int i = 0; i < width * height; ++i)
    for (int c = 0; c < 3; ++c) rgb.push_back(static_cast<float>(color[c]));
  return std::make_shared<const TextureImage>(width, height, std::move(rgb));
}

// texel (x, y) = (x, y, tag): bilinear lookups between texel centres return the continuous
// position, red = s·size − 0.5 and green = v·size − 0.5 with v counted from the bottom row.
std::shared_ptr<const TextureImage> gradient_image(int width, int height, double tag) {
  std::vector<float> rgb;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (const double value : {double(x), double(y), tag}) rgb.push_back(static_cast<float>(value));
  return std::make_shared<const TextureImage>(width, height, std::move(rgb));
}

const Color kFaceColors[6] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 0}, {0, 1, 1}, {1, 0, 1}};

CubeMapEnvironment colored_cube(const Color& multiplier = Color(1)) {
  std::array<std::shared_ptr<const TextureImage>, 6> faces;
  for (int face = 0; face < 6; ++face) faces[face] = constant_image(2, 2, kFaceColors[face]);
  return CubeMapEnvironment(faces, multiplier);
}

TEST(EnvironmentConstant, SameColorEverywhere) {
  const ConstantEnvironment environment(Color(0.2, 0.3, 0.5));
  EXPECT_EQ(environment.type_name(), "constant");
  for (const Vec3& d : {Vec3(1, 0, 0), Vec3(0, -1, 0), normalize(Vec3(1, 2, 3))})
    EXPECT_EQ(environment.radiance(d), Color(0.2, 0.3, 0.5));
}

TEST(EnvironmentCube, AxisDirectionsSeeTheirFaces) {
  const CubeMapEnvironment cube = colored_cube();
  EXPECT_EQ(cube.type_name(), "cube");
  const Vec3 axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (int face = 0; face < 6; ++face) {
    EXPECT_EQ(cube.radiance(axes[face]), kFaceColors[face]) << "face " << face;
    EXPECT_EQ(CubeMapEnvironment::face_coordinates(axes[face]).face, face);
    // The axis looks at the centre of its face.
    EXPECT_EQ(CubeMapEnvironment::face_coordinates(axes[face]).s, 0.5);
    EXPECT_EQ(CubeMapEnvironment::face_coordinates(axes[face]).t, 0.5);
  }
}

TEST(EnvironmentCube, DirectionsNearEdgesAndTiesPickOneFace) {
  const CubeMapEnvironment cube = colored_cube(Color(2));
  const auto face_color = [&](const Vec3& d) { return cube.radiance(normalize(d)); };
  EXPECT_EQ(face_color({1, 0.999, 0.3}), kFaceColors[CubeMapEnvironment::positive_x] * 2);
  EXPECT_EQ(face_color({0.999, 1, 0}), kFaceColors[CubeMapEnvironment::positive_y] * 2);
  EXPECT_EQ(face_color({-0.2, 0.5, -1}), kFaceColors[CubeMapEnvironment::negative_z] * 2);
  EXPECT_EQ(face_color({0.7, -0.7001, 0.7}), kFaceColors[CubeMapEnvironment::negative_y] * 2);
  EXPECT_EQ(face_color({-1, -0.5, 0.9999}), kFaceColors[CubeMapEnvironment::negative_x] * 2);
  // Exact ties: x before y before z.
  EXPECT_EQ(CubeMapEnvironment::face_coordinates({1, 1, 0}).face, CubeMapEnvironment::positive_x);
  EXPECT_EQ(CubeMapEnvironment::face_coordinates({-1, 1, 1}).face, CubeMapEnvironment::negative_x);
  EXPECT_EQ(CubeMapEnvironment::face_coordinates({0, -1, -1}).face, CubeMapEnvironment::negative_y);
  // No direction, no light.
  EXPECT_EQ(cube.radiance({0, 0, 0}), Color(0));
  EXPECT_EQ(cube.radiance({std::nan(""), 1, 0}), Color(0));
}

TEST(EnvironmentCube, FaceCoordinatesFollowTheOpenGLTable) {
  struct Case {
    Vec3 direction;
    CubeMapEnvironment::Face face;
    double s, t;
  };
  // s = (sc/|ma| + 1)/2, t = (tc/|ma| + 1)/2 with OpenGL 4.6 Table 8.19's sc, tc, ma.
  const Case cases[] = {
      {{1, 0.5, -0.25}, CubeMapEnvironment::positive_x, 0.625, 0.25},     // sc = −rz, tc = −ry
      {{-1, 0.5, -0.25}, CubeMapEnvironment::negative_x, 0.375, 0.25},    // sc = +rz, tc = −ry
      {{0.5, 1, -0.25}, CubeMapEnvironment::positive_y, 0.75, 0.375},     // sc = +rx, tc = +rz
      {{0.5, -1, -0.25}, CubeMapEnvironment::negative_y, 0.75, 0.625},    // sc = +rx, tc = −rz
      {{0.5, -0.25, 2}, CubeMapEnvironment::positive_z, 0.625, 0.5625},   // sc = +rx, tc = −ry
      {{0.5, -0.25, -2}, CubeMapEnvironment::negative_z, 0.375, 0.5625},  // sc = −rx, tc = −ry
  };
  for (const Case& c : cases) {
    const auto at = CubeMapEnvironment::face_coordinates(c.direction);
    EXPECT_EQ(at.face, c.face) << c.direction;
    EXPECT_DOUBLE_EQ(at.s, c.s) << c.direction;
    EXPECT_DOUBLE_EQ(at.t, c.t) << c.direction;
    // Length does not matter.
    EXPECT_DOUBLE_EQ(CubeMapEnvironment::face_coordinates(c.direction * 3.5).s, c.s);
  }
}

TEST(EnvironmentCube, GradientFacesGiveTheExactBilinearLookup) {
  constexpr int kSize = 8;
  std::array<std::shared_ptr<const TextureImage>, 6> faces;
  for (int face = 0; face < 6; ++face) faces[face] = gradient_image(kSize, kSize, face);
  const CubeMapEnvironment cube(faces, Color(1), CubeLayout::opengl);
  // The inside layout reads the mirrored column 1 − s: (1 − 0.625)·8 − 0.5 = 2.5.
  EXPECT_EQ(CubeMapEnvironment(faces, Color(1)).radiance({1, 0.5, -0.25}),
            Color(2.5, 5.5, CubeMapEnvironment::positive_x));
  // (1, 0.5, −0.25) → +x at s = 0.625, t = 0.25: column position 0.625·8 − 0.5 = 4.5; t runs
  // down from the top row, so the row position from the bottom is (1 − 0.25)·8 − 0.5 = 5.5.
  EXPECT_EQ(cube.radiance({1, 0.5, -0.25}), Color(4.5, 5.5, CubeMapEnvironment::positive_x));
  // (0.5, −1, −0.25) → −y at s = 0.75, t = 0.625.
  EXPECT_EQ(cube.radiance({0.5, -1, -0.25}), Color(5.5, 2.5, CubeMapEnvironment::negative_y));
  // (0.5, −0.25, −2) → −z at s = 0.375, t = 0.5625.
  EXPECT_EQ(cube.radiance({0.5, -0.25, -2}), Color(2.5, 3, CubeMapEnvironment::negative_z));
  // A unit direction gives the same up to rounding.
  const Color unit = cube.radiance(normalize(Vec3(1, 0.5, -0.25)));
  EXPECT_NEAR(unit.r, 4.5, 1e-12);
  EXPECT_NEAR(unit.g, 5.5, 1e-12);
  // t = 0 is the file's top row: on +x, looking almost straight up (+y) reads the top row
  // (y = 7 counted from the bottom), and towards −z the right column.
  EXPECT_NEAR(cube.radiance({1, 0.999, 0}).g, kSize - 1, 1e-12);
  EXPECT_NEAR(cube.radiance({1, 0, -0.999}).r, kSize - 1, 1e-12);
  // On +z the top row is towards +y and the right column towards +x; on −z the right column
  // is towards −x.
  const Color corner = cube.radiance({0.999, 0.999, 1});
  EXPECT_EQ(corner.b, CubeMapEnvironment::positive_z);
  EXPECT_NEAR(corner.r, kSize - 1, 1e-12);
  EXPECT_NEAR(corner.g, kSize - 1, 1e-12);
  EXPECT_NEAR(cube.radiance({-0.999, 0, -1}).r, kSize - 1, 1e-12);
  EXPECT_NEAR(cube.radiance({0.999, 0, -1}).r, 0, 1e-12);
}

TEST(EnvironmentCube, FacesMustBeSquareEqualAndPresent) {
  std::array<std::shared_ptr<const TextureImage>, 6> faces;
  for (int face = 0; face < 6; ++face) faces[face] = constant_image(4, 4, Color(1));
  EXPECT_NO_THROW(CubeMapEnvironment(faces, Color(1)));
  auto non_square = faces;
  non_square[3] = constant_image(4, 2, Color(1));
  EXPECT_THROW(CubeMapEnvironment(non_square, Color(1)), std::invalid_argument);
  auto mismatched = faces;
  mismatched[5] = constant_image(8, 8, Color(1));
  EXPECT_THROW(CubeMapEnvironment(mismatched, Color(1)), std::invalid_argument);
  auto missing = faces;
  missing[1] = nullptr;
  EXPECT_THROW(CubeMapEnvironment(missing, Color(1)), std::invalid_argument);
}

// 8×4 panorama with texel (x, y) = (x, y, 0): red = u·8 − 0.5, green = (1 − v)·4 − 0.5.
EquirectangularEnvironment panorama(const Vec3& up = {0, 1, 0}, const Vec3& forward = {0, 0, -1}) {
  return EquirectangularEnvironment(gradient_image(8, 4, 0), up, forward, Color(1));
}

TEST(EnvironmentEquirectangular, ForwardIsTheCentreUpTheTopRow) {
  const EquirectangularEnvironment environment = panorama();
  EXPECT_EQ(environment.type_name(), "equirectangular");
  const Vec3 up(0, 1, 0), forward(0, 0, -1), right = cross(forward, up);  // right = +x
  EXPECT_EQ(right, Vec3(1, 0, 0));
  // Forward: the image centre, u = 0.5, v = 0.5.
  EXPECT_DOUBLE_EQ(environment.panorama_coordinates(forward).x, 0.5);
  EXPECT_DOUBLE_EQ(environment.panorama_coordinates(forward).y, 0.5);
  EXPECT_EQ(environment.radiance(forward), Color(3.5, 1.5, 0));
  // Up: the top row (clamped), down: the bottom row.
  EXPECT_DOUBLE_EQ(environment.panorama_coordinates(up).y, 0);
  EXPECT_EQ(environment.radiance(up).g, 3);
  EXPECT_DOUBLE_EQ(environment.panorama_coordinates(-up).y, 1);
  EXPECT_EQ(environment.radiance(-up).g, 0);
  // Right at u = 0.75, left at u = 0.25, both on the horizon.
  EXPECT_DOUBLE_EQ(environment.panorama_coordinates(right).x, 0.75);
  EXPECT_EQ(environment.radiance(right), Color(5.5, 1.5, 0));
  EXPECT_DOUBLE_EQ(environment.panorama_coordinates(-right).x, 0.25);
  EXPECT_EQ(environment.radiance(-right), Color(1.5, 1.5, 0));
  // 45° above the horizon: v = 1/4, a quarter of the way down.
  EXPECT_NEAR(environment.panorama_coordinates(normalize(forward + up)).y, 0.25, 1e-15);
}

TEST(EnvironmentEquirectangular, BehindIsTheSeamBlendingLastAndFirstColumns) {
  const EquirectangularEnvironment environment = panorama();
  const Vec3 behind(0, 0, 1);
  const double u = environment.panorama_coordinates(behind).x;
  EXPECT_TRUE(u == 0 || u == 1) << u;
  // Columns 7 and 0 blended half and half: red = (7 + 0)/2, on the horizon green = 1.5.
  EXPECT_EQ(environment.radiance(behind), Color(3.5, 1.5, 0));
  // Just either side of the seam: continuous, no jump to one column.
  const Color left_of_seam = environment.radiance(normalize(Vec3(-1e-9, 0, 1)));
  const Color right_of_seam = environment.radiance(normalize(Vec3(1e-9, 0, 1)));
  EXPECT_NEAR(left_of_seam.r, 3.5, 1e-6);
  EXPECT_NEAR(right_of_seam.r, 3.5, 1e-6);
}

TEST(EnvironmentEquirectangular, OtherFramesAndNonOrthogonalForward) {
  // Up +z, forward +x: right = x × z = −y.
  const EquirectangularEnvironment z_up = panorama({0, 0, 1}, {1, 0, 0});
  EXPECT_DOUBLE_EQ(z_up.panorama_coordinates({1, 0, 0}).x, 0.5);
  EXPECT_DOUBLE_EQ(z_up.panorama_coordinates({0, -1, 0}).x, 0.75);
  EXPECT_DOUBLE_EQ(z_up.panorama_coordinates({0, 0, 1}).y, 0);
  // Forward tilted towards up keeps only its horizontal part; up need not be unit.
  const EquirectangularEnvironment tilted = panorama({0, 3, 0}, {0, 0.5, -1});
  EXPECT_DOUBLE_EQ(tilted.panorama_coordinates({0, 0, -1}).x, 0.5);
  EXPECT_DOUBLE_EQ(tilted.panorama_coordinates({0, 0, -1}).y, 0.5);
  EXPECT_THROW(panorama({0, 1, 0}, {0, -2, 0}), std::invalid_argument);
  EXPECT_THROW(panorama({0, 0, 0}, {0, 0, -1}), std::invalid_argument);
  EXPECT_THROW(panorama({0, 1, 0}, {0, 0, 0}), std::invalid_argument);
  EXPECT_THROW(EquirectangularEnvironment(nullptr, {0, 1, 0}, {0, 0, -1}, Color(1)), std::invalid_argument);
}

TEST(EnvironmentEquirectangular, MultiplierScales) {
  const EquirectangularEnvironment environment(constant_image(4, 2, Color(0.5, 1, 2)), {0, 1, 0}, {0, 0, -1},
                                               Color(2, 3, 4));
  EXPECT_EQ(environment.radiance(normalize(Vec3(0.3, -0.2, 0.9))), Color(1, 3, 8));
}

}  // namespace
}  // namespace candela
