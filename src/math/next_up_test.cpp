#include "math/next_up.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

#include "math/constants.h"
#include "math/pcg32.h"

namespace candela {
namespace {

TEST(NextUp, EqualsNextafterTowardsInfinity) {
  constexpr double kMax = std::numeric_limits<double>::max();
  constexpr double kDenormal = std::numeric_limits<double>::denorm_min();
  constexpr double kMinNormal = std::numeric_limits<double>::min();
  const double values[] = {0.0,  -0.0,  kDenormal,  -kDenormal,    kMinNormal,      -kMinNormal, 1.0,
                           -1.0, 0.5,   -0.5,       1e-300,        -1e-300,         3.75e200,    -3.75e200,
                           kMax, -kMax, -kInfinity, 1.0 - 0x1p-53, -(1.0 + 0x1p-52)};
  for (const double t : values) {
    const double expected = std::nextafter(t, kInfinity);
    EXPECT_EQ(std::bit_cast<uint64_t>(next_up(t)), std::bit_cast<uint64_t>(expected)) << t;
  }
  EXPECT_EQ(next_up(kMax), kInfinity);
  EXPECT_EQ(next_up(kInfinity), kInfinity);
  EXPECT_EQ(next_up(-kMax), -std::nextafter(kMax, 0.0));
  Pcg32 random(7, 1);
  for (int i = 0; i < 100000; ++i) {
    // Any bit pattern but NaN: every sign, exponent and mantissa.
    const uint64_t bits = (uint64_t{random.next_uint()} << 32) | random.next_uint();
    const double t = std::bit_cast<double>(bits);
    if (std::isnan(t)) continue;
    ASSERT_EQ(std::bit_cast<uint64_t>(next_up(t)), std::bit_cast<uint64_t>(std::nextafter(t, kInfinity)))
        << t;
  }
}

TEST(NextUp, FloatEqualsNextafterTowardsInfinity) {
  constexpr float kMax = std::numeric_limits<float>::max();
  constexpr float kInfinityF = std::numeric_limits<float>::infinity();
  const float values[] = {0.0f,
                          -0.0f,
                          std::numeric_limits<float>::denorm_min(),
                          -std::numeric_limits<float>::min(),
                          1.0f,
                          -1.0f,
                          1.59698451f,
                          -3.75e30f,
                          kMax,
                          -kMax,
                          -kInfinityF};
  for (const float t : values)
    EXPECT_EQ(std::bit_cast<uint32_t>(next_up(t)), std::bit_cast<uint32_t>(std::nextafter(t, kInfinityF)))
        << t;
  EXPECT_EQ(next_up(kInfinityF), kInfinityF);
  Pcg32 random(7, 2);
  for (int i = 0; i < 100000; ++i) {
    const float t = std::bit_cast<float>(random.next_uint());
    if (std::isnan(t)) continue;
    ASSERT_EQ(std::bit_cast<uint32_t>(next_up(t)), std::bit_cast<uint32_t>(std::nextafter(t, kInfinityF)))
        << t;
  }
}

}  // namespace
}  // namespace candela
