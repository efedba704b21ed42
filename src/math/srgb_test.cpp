#include "math/srgb.h"

#include <gtest/gtest.h>

#include <cmath>

namespace candela {
namespace {

TEST(Srgb, DecodeMatchesTheStandard) {
  EXPECT_EQ(srgb_decode(0), 0);
  EXPECT_DOUBLE_EQ(srgb_decode(1), 1);
  EXPECT_DOUBLE_EQ(srgb_decode(0.04045), 0.04045 / 12.92);
  EXPECT_DOUBLE_EQ(srgb_decode(0.5), std::pow(0.555 / 1.055, 2.4));
  // The two pieces meet at the threshold up to the rounding of the standard's constants (2e-9).
  EXPECT_NEAR(srgb_decode(0.04045 + 1e-12), srgb_decode(0.04045), 1e-8);
}

TEST(Srgb, EncodeMatchesTheStandardAndInvertsDecode) {
  EXPECT_EQ(srgb_encode(0), 0);
  EXPECT_DOUBLE_EQ(srgb_encode(1), 1);
  EXPECT_DOUBLE_EQ(srgb_encode(0.0031308), 12.92 * 0.0031308);
  EXPECT_DOUBLE_EQ(srgb_encode(0.5), 1.055 * std::pow(0.5, 1 / 2.4) - 0.055);
  for (double linear = 0; linear <= 1; linear += 1.0 / 64)
    EXPECT_NEAR(srgb_decode(srgb_encode(linear)), linear, 1e-12) << linear;
}

}  // namespace
}  // namespace candela
