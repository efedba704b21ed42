// direction_of (math/direction.h): every finite non-zero vector has a direction, however large or
// small its components; ordinary vectors give exactly normalize(v).
#include "math/direction.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace candela {
namespace {

TEST(DirectionOf, HugeAndTinyComponentsHaveADirection) {
  // length() overflows to infinity here (v / length(v) is zero) ...
  const auto huge = direction_of({1e200, 1e200, 0});
  ASSERT_TRUE(huge.has_value());
  EXPECT_NEAR(huge->x, std::sqrt(0.5), 1e-15);
  EXPECT_NEAR(huge->y, std::sqrt(0.5), 1e-15);
  EXPECT_EQ(huge->z, 0);
  const auto largest = direction_of({-std::numeric_limits<double>::max(), 0, 0});
  ASSERT_TRUE(largest.has_value());
  EXPECT_EQ(largest->x, -1);
  // ... and underflows to 0 here (the vector was called zero).
  const auto tiny = direction_of({0, 3e-200, 4e-200});
  ASSERT_TRUE(tiny.has_value());
  EXPECT_NEAR(tiny->y, 0.6, 1e-15);
  EXPECT_NEAR(tiny->z, 0.8, 1e-15);
  const auto denormal = direction_of({0, 0, std::numeric_limits<double>::denorm_min()});
  ASSERT_TRUE(denormal.has_value());
  EXPECT_EQ(denormal->z, 1);
}

TEST(DirectionOf, ZeroAndNonFiniteHaveNone) {
  EXPECT_FALSE(direction_of({0, 0, 0}).has_value());
  EXPECT_FALSE(direction_of({0, -0.0, 0}).has_value());
  EXPECT_FALSE(direction_of({std::numeric_limits<double>::infinity(), 0, 0}).has_value());
  EXPECT_FALSE(direction_of({1, std::numeric_limits<double>::quiet_NaN(), 0}).has_value());
}

TEST(DirectionOf, OrdinaryVectorsGiveExactlyNormalize) {
  for (const Vec3 v : {Vec3{1, 2, 3}, Vec3{-0.3, 1e-5, 7e10}, Vec3{1e150, 0, 1}, Vec3{1e-150, 1e-151, 0}}) {
    const auto unit = direction_of(v);
    ASSERT_TRUE(unit.has_value());
    const Vec3 expected = normalize(v);
    EXPECT_EQ(unit->x, expected.x);
    EXPECT_EQ(unit->y, expected.y);
    EXPECT_EQ(unit->z, expected.z);
  }
}

}  // namespace
}  // namespace candela
