// Helpers shared by the shape, texture and noise tests.
#pragma once

#include <gtest/gtest.h>

#include "math/pcg32.h"
#include "math/ray.h"

namespace candela::testing {

inline Ray make_ray(Vec3 origin, Vec3 direction) {
  return Ray{origin, normalize(direction)};
}

inline void expect_vec_near(const Vec3& actual, const Vec3& expected, double tolerance) {
  EXPECT_NEAR(actual.x, expected.x, tolerance) << actual << " vs " << expected;
  EXPECT_NEAR(actual.y, expected.y, tolerance) << actual << " vs " << expected;
  EXPECT_NEAR(actual.z, expected.z, tolerance) << actual << " vs " << expected;
}

// A uniformly random point of the cube [−extent, extent]³.
inline Vec3 random_point(Pcg32& rng, double extent) {
  return {(2 * rng.next_double() - 1) * extent, (2 * rng.next_double() - 1) * extent,
          (2 * rng.next_double() - 1) * extent};
}

}  // namespace candela::testing
