#include "math/transform.h"

#include <fmt/format.h>

#include <Eigen/SVD>
#include <cmath>
#include <stdexcept>

#include "math/constants.h"
#include "math/direction.h"

namespace candela {

Transform Transform::from_matrix(const Eigen::Matrix4d& matrix) {
  if (!matrix.allFinite()) throw std::invalid_argument("matrix has non-finite entries");
  if (matrix(3, 0) != 0 || matrix(3, 1) != 0 || matrix(3, 2) != 0 || matrix(3, 3) != 1)
    throw std::invalid_argument("matrix must be affine (last row 0 0 0 1)");
  // Singular relative to its own size: the determinant of the columns scaled to unit length (1 for
  // orthogonal columns, 0 for dependent ones), so any scale, however small, is accepted and
  // columns that are (nearly) parallel are not. Scaling each column first keeps the product of
  // three lengths from overflowing (entries of 1e300 were called singular) or underflowing
  // (scales of 1e-150); stableNorm does the same for each length.
  Eigen::Matrix3d unit_columns = matrix.topLeftCorner<3, 3>();
  for (int c = 0; c < 3; ++c) {
    const double column_length = unit_columns.col(c).stableNorm();
    if (!(column_length > 0))
      throw std::invalid_argument("matrix is singular (a column of its 3×3 part is zero)");
    unit_columns.col(c) /= column_length;
  }
  if (!(std::fabs(unit_columns.determinant()) > 1e-12)) throw std::invalid_argument("matrix is singular");
  return Transform(matrix, matrix.inverse());
}

Transform Transform::translate(const Vec3& offset) {
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m(0, 3) = offset.x;
  m(1, 3) = offset.y;
  m(2, 3) = offset.z;
  Eigen::Matrix4d inverse = Eigen::Matrix4d::Identity();
  inverse(0, 3) = -offset.x;
  inverse(1, 3) = -offset.y;
  inverse(2, 3) = -offset.z;
  return Transform(m, inverse);
}

Transform Transform::scale(const Vec3& factors) {
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m(0, 0) = factors.x;
  m(1, 1) = factors.y;
  m(2, 2) = factors.z;
  return from_matrix(m);
}

Transform Transform::rotate(double angle_degrees, const Vec3& axis) {
  const std::optional<Vec3> unit = direction_of(axis);
  if (!unit) throw std::invalid_argument("rotation axis must be non-zero and finite");
  const Eigen::Vector3d a(unit->x, unit->y, unit->z);
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m.topLeftCorner<3, 3>() = Eigen::AngleAxisd(degrees_to_radians(angle_degrees), a).toRotationMatrix();
  Eigen::Matrix4d inverse = Eigen::Matrix4d::Identity();
  inverse.topLeftCorner<3, 3>() = m.topLeftCorner<3, 3>().transpose();
  return Transform(m, inverse);
}

Transform Transform::operator*(const Transform& other) const {
  return Transform(matrix_ * other.matrix_, other.inverse_ * inverse_);
}

Transform Transform::inverse() const {
  return Transform(inverse_, matrix_);
}

bool Transform::is_identity() const {
  return matrix_ == Eigen::Matrix4d::Identity();
}

Vec3 Transform::point(const Vec3& p) const {
  const auto& m = matrix_;
  return {m(0, 0) * p.x + m(0, 1) * p.y + m(0, 2) * p.z + m(0, 3),
          m(1, 0) * p.x + m(1, 1) * p.y + m(1, 2) * p.z + m(1, 3),
          m(2, 0) * p.x + m(2, 1) * p.y + m(2, 2) * p.z + m(2, 3)};
}

Vec3 Transform::vector(const Vec3& v) const {
  const auto& m = matrix_;
  return {m(0, 0) * v.x + m(0, 1) * v.y + m(0, 2) * v.z, m(1, 0) * v.x + m(1, 1) * v.y + m(1, 2) * v.z,
          m(2, 0) * v.x + m(2, 1) * v.y + m(2, 2) * v.z};
}

Vec3 Transform::normal(const Vec3& n) const {
  const auto& inv = inverse_;  // (M^-1)^T n
  return {inv(0, 0) * n.x + inv(1, 0) * n.y + inv(2, 0) * n.z,
          inv(0, 1) * n.x + inv(1, 1) * n.y + inv(2, 1) * n.z,
          inv(0, 2) * n.x + inv(1, 2) * n.y + inv(2, 2) * n.z};
}

Bounds3 Transform::bounds(const Bounds3& b) const {
  Bounds3 result;
  if (b.empty()) return result;
  // An unbounded shape (a plane) stays unbounded: inf × 0 would give NaN corners otherwise.
  if (!b.is_finite()) return {{-kInfinity, -kInfinity, -kInfinity}, {kInfinity, kInfinity, kInfinity}};
  for (int corner = 0; corner < 8; ++corner) {
    const Vec3 p{(corner & 1) ? b.upper.x : b.lower.x, (corner & 2) ? b.upper.y : b.lower.y,
                 (corner & 4) ? b.upper.z : b.lower.z};
    result.extend(point(p));
  }
  return result;
}

std::string transform_problem(const Transform& transform) {
  const Eigen::Matrix4d& matrix = transform.matrix();
  const double largest = matrix.allFinite() ? matrix.cwiseAbs().maxCoeff() : kInfinity;
  if (!(largest <= kMaxSceneMagnitude))
    return fmt::format(
        "the composed transform overflows: an entry reaches {:.3g}, above {:g} (a product of "
        "too many scales or offsets)",
        largest, kMaxSceneMagnitude);
  const Eigen::Matrix3d linear = matrix.topLeftCorner<3, 3>();
  const Eigen::Vector3d singular =
      Eigen::JacobiSVD<Eigen::Matrix3d>(linear).singularValues();  // largest first
  if (!transform.inverse().matrix().allFinite() || !(singular(2) >= 1 / kMaxSceneMagnitude))
    return fmt::format(
        "the composed transform underflows: it shrinks a direction to {:.3g} of its length, below "
        "{:g} (a product of too many small scales)",
        singular(2), 1 / kMaxSceneMagnitude);
  const double condition = singular(0) / singular(2);
  if (!(condition <= kMaxTransformCondition))
    return fmt::format(
        "the composed transform stretches one direction {:.3g} times more than another (at most {:g})",
        condition, kMaxTransformCondition);
  return {};
}

}  // namespace candela
