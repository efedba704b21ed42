#include "math/transform.h"

#include <gtest/gtest.h>

#include <string>

namespace candela {
namespace {

void expect_near(const Vec3& a, const Vec3& b) {
  EXPECT_NEAR(a.x, b.x, 1e-12);
  EXPECT_NEAR(a.y, b.y, 1e-12);
  EXPECT_NEAR(a.z, b.z, 1e-12);
}

TEST(Transform, ComposesInOrderAndInverts) {
  // Scale first, then rotate 90° about z, then translate.
  const Transform t =
      Transform::translate({1, 2, 3}) * Transform::rotate(90, {0, 0, 1}) * Transform::scale({2, 2, 2});
  expect_near(t.point({1, 0, 0}), {1, 4, 3});
  expect_near(t.vector({1, 0, 0}), {0, 2, 0});
  expect_near(t.inverse().point(t.point({0.3, -0.7, 5})), {0.3, -0.7, 5});
}

TEST(Transform, NormalsUseTheInverseTranspose) {
  // Under a non-uniform scale the normal of the plane x + y = 1 stays perpendicular to it.
  const Transform t = Transform::scale({4, 1, 1});
  const Vec3 tangent = t.vector({1, -1, 0});
  const Vec3 normal = t.normal({1, 1, 0});
  EXPECT_NEAR(dot(tangent, normal), 0, 1e-12);
}

TEST(Transform, RejectsSingularAndProjectiveMatrices) {
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m(2, 2) = 0;
  EXPECT_THROW(Transform::from_matrix(m), std::invalid_argument);
  m = Eigen::Matrix4d::Identity();
  m(3, 0) = 1;
  EXPECT_THROW(Transform::from_matrix(m), std::invalid_argument);
  EXPECT_THROW(Transform::rotate(10, {0, 0, 0}), std::invalid_argument);
}

// Entries of 1e300 were called "matrix is singular" (the product of the column lengths
// overflowed), and so were scales of 1e-150 (it underflowed). Neither is singular; columns that
// are dependent, however large or small, still are.
TEST(Transform, SingularityDoesNotDependOnTheMatrixScale) {
  for (const double scale : {1e300, 1e-150, 1e-300}) {
    Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
    m.topLeftCorner<3, 3>() *= scale;
    m(0, 1) = 0.5 * scale;
    EXPECT_NO_THROW(Transform::from_matrix(m)) << scale;
    m(1, 0) = m(0, 0), m(1, 1) = m(0, 1);  // the second row equals the first
    try {
      (void)Transform::from_matrix(m);
      ADD_FAILURE() << "accepted a singular matrix at scale " << scale;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("singular"), std::string::npos) << e.what();
    }
  }
  // A rotation about an axis of tiny or huge components (its length under- or overflows).
  expect_near(Transform::rotate(90, {0, 0, 1e-200}).vector({1, 0, 0}), {0, 1, 0});
  expect_near(Transform::rotate(90, {0, 0, 1e300}).vector({1, 0, 0}), {0, 1, 0});
}

TEST(Transform, BoundsOfARotatedBox) {
  const Bounds3 b = Transform::rotate(45, {0, 0, 1}).bounds({{-1, -1, 0}, {1, 1, 0}});
  EXPECT_NEAR(b.upper.x, std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(b.lower.y, -std::sqrt(2.0), 1e-12);
}

TEST(Transform, UnboundedBoundsStayUnbounded) {
  // A transformed plane used to get empty bounds (inf × 0 = NaN) and could be dropped.
  const Bounds3 infinite{{-kInfinity, -kInfinity, -kInfinity}, {kInfinity, kInfinity, kInfinity}};
  const Bounds3 b = (Transform::translate({0, 3, 0}) * Transform::rotate(30, {1, 0, 0})).bounds(infinite);
  EXPECT_FALSE(b.empty());
  EXPECT_EQ(b.lower.x, -kInfinity);
  EXPECT_EQ(b.upper.y, kInfinity);
}

}  // namespace
}  // namespace candela
