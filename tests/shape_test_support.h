// Helpers shared by the shape tests.
#pragma once

#include <gtest/gtest.h>

#include "math/ray.h"

namespace candela::testing {

inline Ray make_ray(Vec3 origin, Vec3 direction) {
  return Ray{origin, normalize(direction)};
}

inline void expect_vec_near(const Vec3& actual, const Vec3& expected, double tolerance) {
  EXPECT_NEAR(actual.x, expected.x, tolerance);
  EXPECT_NEAR(actual.y, expected.y, tolerance);
  EXPECT_NEAR(actual.z, expected.z, tolerance);
}

}  // namespace candela::testing
