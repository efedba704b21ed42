// Affine transforms as 4x4 matrices (Eigen), with the inverse kept alongside.
#pragma once

#include <Eigen/Dense>
#include <string>

#include "math/bounds.h"
#include "math/ray.h"
#include "math/vector.h"

namespace candela {

class Transform {
 public:
  Transform() : matrix_(Eigen::Matrix4d::Identity()), inverse_(Eigen::Matrix4d::Identity()) {}
  // Throws std::invalid_argument when the matrix is singular or not affine.
  static Transform from_matrix(const Eigen::Matrix4d& matrix);
  static Transform translate(const Vec3& offset);
  static Transform scale(const Vec3& factors);
  // Rotation by angle_degrees about axis (right-handed, counter-clockwise looking down the axis).
  static Transform rotate(double angle_degrees, const Vec3& axis);

  // this * other: other is applied first.
  Transform operator*(const Transform& other) const;
  Transform inverse() const;
  bool is_identity() const;
  const Eigen::Matrix4d& matrix() const { return matrix_; }

  Vec3 point(const Vec3& p) const;
  Vec3 vector(const Vec3& v) const;
  Vec3 normal(const Vec3& n) const;  // by the inverse transpose, not normalised
  Bounds3 bounds(const Bounds3& b) const;

 private:
  Transform(const Eigen::Matrix4d& m, const Eigen::Matrix4d& inverse) : matrix_(m), inverse_(inverse) {}
  Eigen::Matrix4d matrix_;
  Eigen::Matrix4d inverse_;
};

// The largest condition number (largest over smallest singular value of the linear part)
// a transform may have: beyond it, an object is so much thinner in one direction than in another
// that double precision no longer resolves it (10^12 leaves about four of its sixteen digits).
inline constexpr double kMaxTransformCondition = 1e12;

// What is wrong with a transform that was composed from legal steps, or "": an entry beyond
// kMaxSceneMagnitude or not finite (a product of scales or offsets that overflowed), a smallest
// singular value below 1 / kMaxSceneMagnitude (a product that underflowed towards singular), or a
// condition number beyond kMaxTransformCondition.
std::string transform_problem(const Transform& transform);

}  // namespace candela
