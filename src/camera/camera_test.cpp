#include <gtest/gtest.h>

#include <cmath>

#include "camera/orthographic_camera.h"
#include "camera/perspective_camera.h"
#include "math/constants.h"

namespace candela {
namespace {

TEST(PerspectiveCamera, FollowsTheViewingSystemOf000Section5_2) {
  // Eye at E looking down -z with up +y: G = (0,0,-1), X = G×U = (1,0,0), Y = X×G = (0,1,0).
  const Vec3 eye{1, 2, 3};
  const int width = 8, height = 4;
  const double fov = 90;  // 2θ; tan θ = 1
  const PerspectiveCamera camera(eye, eye + Vec3{0, 0, -1}, {0, 1, 0}, fov, width, height);
  const double tan_theta = 1.0;
  const double tan_phi = tan_theta * height / width;  // square pixels
  for (int row = 0; row < height; ++row) {
    for (int i = 0; i < width; ++i) {
      // The seed counts j from the bottom row; image rows run from the top.
      const int j = height - 1 - row;
      const double x_view = (i + 0.5) / width, y_view = (j + 0.5) / height;
      const Vec3 P =
          Vec3{0, 0, -1} + Vec3{tan_theta, 0, 0} * (2 * x_view - 1) + Vec3{0, tan_phi, 0} * (2 * y_view - 1);
      const Ray ray = camera.generate_ray(i + 0.5, row + 0.5);
      EXPECT_EQ(ray.origin, eye);
      const Vec3 expected = normalize(P);
      EXPECT_NEAR(ray.direction.x, expected.x, 1e-15);
      EXPECT_NEAR(ray.direction.y, expected.y, 1e-15);
      EXPECT_NEAR(ray.direction.z, expected.z, 1e-15);
    }
  }
  // The image corners span the full field of view.
  const Ray corner = camera.generate_ray(width, 0);  // top-right corner
  EXPECT_NEAR(corner.direction.x / -corner.direction.z, tan_theta, 1e-15);
  EXPECT_NEAR(corner.direction.y / -corner.direction.z, tan_phi, 1e-15);
}

TEST(PerspectiveCamera, CentreRayLooksAtTheTarget) {
  const PerspectiveCamera camera({0, 0, 0}, {3, 4, 0}, {0, 0, 1}, 40, 101, 51);
  const Ray ray = camera.generate_ray(50.5, 25.5);
  EXPECT_NEAR(ray.direction.x, 0.6, 1e-14);
  EXPECT_NEAR(ray.direction.y, 0.8, 1e-14);
}

TEST(PerspectiveCamera, RejectsDegenerateViews) {
  EXPECT_THROW(PerspectiveCamera({0, 0, 0}, {0, 0, 0}, {0, 1, 0}, 60, 4, 4), std::invalid_argument);
  EXPECT_THROW(PerspectiveCamera({0, 0, 0}, {0, 1, 0}, {0, 1, 0}, 60, 4, 4), std::invalid_argument);
}

TEST(OrthographicCamera, RaysArePerpendicularToTheWindow) {
  // 001: u = l + (r − l)(i + 0.5)/Nx, v = b + (t − b)(j + 0.5)/Ny, direction G.
  const OrthographicCamera camera({0, 0, 10}, {0, 0, 0}, {0, 1, 0}, -4, 4, -2, 2, 4, 2);
  const Ray ray = camera.generate_ray(0.5, 0.5);  // top-left pixel: i = 0, j = Ny − 1 = 1
  EXPECT_NEAR(ray.origin.x, -4 + 8 * 0.5 / 4, 1e-15);
  EXPECT_NEAR(ray.origin.y, -2 + 4 * 1.5 / 2, 1e-15);
  EXPECT_NEAR(ray.origin.z, 10, 1e-15);
  EXPECT_EQ(ray.direction, (Vec3{0, 0, -1}));
}

// view_projection is generate_ray read backwards: a point on the ray through image position
// (x, y) projects to ndc (2x/width − 1, 1 − 2y/height), in front of the near plane.
void expect_projection_matches_rays(const Camera& camera) {
  const Eigen::Matrix4d clip_from_world = camera.view_projection(0.5, 100);
  for (const auto& [x, y] :
       {std::pair{0.5, 0.5}, std::pair{13.25, 7.75}, std::pair{31.5, 23.5}, std::pair{16.0, 12.0}}) {
    const Ray ray = camera.generate_ray(x, y);
    for (const double t : {1.0, 5.0, 40.0}) {
      const Vec3 p = ray.at(t);
      const Eigen::Vector4d clip = clip_from_world * Eigen::Vector4d(p.x, p.y, p.z, 1);
      ASSERT_GT(clip.w(), 0);
      EXPECT_NEAR(clip.x() / clip.w(), 2 * x / camera.width() - 1, 1e-12) << x << "," << y << " t " << t;
      EXPECT_NEAR(clip.y() / clip.w(), 1 - 2 * y / camera.height(), 1e-12) << x << "," << y << " t " << t;
      EXPECT_GT(clip.z() / clip.w(), -1);
      EXPECT_LT(clip.z() / clip.w(), 1);
    }
  }
  // Depth grows with distance along the view direction.
  const Vec3 eye = camera.eye_position(), ahead = camera.view_direction();
  const auto depth = [&](double t) {
    const Vec3 p = eye + ahead * t;
    const Eigen::Vector4d clip = clip_from_world * Eigen::Vector4d(p.x, p.y, p.z, 1);
    return clip.z() / clip.w();
  };
  EXPECT_NEAR(depth(0.5), -1, 1e-12);
  EXPECT_NEAR(depth(100), 1, 1e-12);
  EXPECT_LT(depth(2), depth(3));
}

TEST(PerspectiveCamera, ViewProjectionMatchesGenerateRay) {
  expect_projection_matches_rays(PerspectiveCamera({1, 2, 3}, {-2, 0.5, -4}, {0.1, 1, 0}, 70, 32, 24));
}

TEST(OrthographicCamera, ViewProjectionMatchesGenerateRay) {
  expect_projection_matches_rays(
      OrthographicCamera({1, 2, 3}, {-2, 0.5, -4}, {0, 1, 0}, -3, 2, -1, 2.5, 32, 24));
}

}  // namespace
}  // namespace candela
