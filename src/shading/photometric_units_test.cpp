// Photometric units (shading/photometric_units.h): blackbody colours of unit luminance with the
// expected hue, and the one conversion.
#include "shading/photometric_units.h"

#include <gtest/gtest.h>

namespace candela {
namespace {

TEST(PhotometricUnits, BlackbodyColoursHaveUnitLuminanceAndTheirHue) {
  for (const double kelvin : {1000.0, 1900.0, 2700.0, 4000.0, 6500.0, 10000.0, 40000.0})
    EXPECT_NEAR(luminance(blackbody_color(kelvin)), 1, 1e-12) << kelvin;
  // Near D65's 6,504 K a blackbody is close to the sRGB white (D65 lies just off the Planckian
  // locus): every channel within 8 % of the others.
  const Color daylight = blackbody_color(6500);
  EXPECT_NEAR(daylight.r / daylight.g, 1, 0.08);
  EXPECT_NEAR(daylight.b / daylight.g, 1, 0.08);
  // Incandescent 2,700 K: red over green over blue; 10,000 K: bluish.
  const Color warm = blackbody_color(2700), cool = blackbody_color(10000);
  EXPECT_GT(warm.r, warm.g);
  EXPECT_GT(warm.g, warm.b);
  EXPECT_GT(warm.b, 0);
  EXPECT_GT(cool.b, cool.g);
  EXPECT_GT(cool.b, cool.r);
  // Below about 1,900 K blue is outside the gamut: clipped to 0, never negative.
  EXPECT_EQ(blackbody_color(1000).b, 0);
  // Out of range: the ends.
  EXPECT_EQ(blackbody_color(100), blackbody_color(1000));
}

TEST(PhotometricUnits, OneEfficacyConvertsEveryAmount) {
  EXPECT_EQ(kLuminousEfficacy, 179);
  const Color c = radiometric(358, Color(0.5, 0.5, 0.5));  // the colour's own luminance drops out
  EXPECT_NEAR(c.r, 2, 1e-12);
  EXPECT_NEAR(c.b, 2, 1e-12);
  EXPECT_NEAR(luminance(radiometric(179, Color(1, 0.2, 0.1))), 1, 1e-12);
}

}  // namespace
}  // namespace candela
