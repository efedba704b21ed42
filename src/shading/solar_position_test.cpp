// Solar position (shading/solar_position.h) against published positions.
#include "shading/solar_position.h"

#include <gtest/gtest.h>

namespace candela {
namespace {

TEST(SolarPosition, MatchesNrelSpasWorkedExample) {
  // Reda and Andreas 2004 (NREL SPA), the worked example: Golden, Colorado, 17 October 2003,
  // 12:30:30 local (UT − 7), latitude 39.742476° N, longitude 105.1786° W: topocentric zenith
  // 50.11162° (elevation 39.88838° with refraction), azimuth 194.34024° from north. Michalsky's
  // algorithm is good to about 0.01° here (the SPA's parallax is 0.002°).
  const SolarPosition sun =
      solar_position(2003, 10, 17, 12 + 30.0 / 60 + 30.0 / 3600, -7, 39.742476, -105.1786);
  EXPECT_NEAR(sun.elevation_degrees, 90 - 50.11162, 0.03);
  EXPECT_NEAR(sun.azimuth_degrees, 194.34024, 0.03);
}

TEST(SolarPosition, NoonAtTheEquinoxAndTheSolsticeAndDaysOfTheYear) {
  // Local apparent noon on the equator near the March equinox: the sun close to the zenith.
  const SolarPosition equinox = solar_position(2026, 3, 20, 12 + 7.0 / 60, 0, 0, 0);
  EXPECT_GT(equinox.elevation_degrees, 89);
  // Greenwich (51.48° N) at the June solstice, 13:02 BST (UT + 1): elevation 90 − 51.48 + 23.44.
  const SolarPosition solstice = solar_position(2026, 6, 21, 13 + 2.0 / 60, 1, 51.4769, 0);
  EXPECT_NEAR(solstice.elevation_degrees, 90 - 51.4769 + 23.44, 0.2);
  EXPECT_NEAR(solstice.azimuth_degrees, 180, 1.5);
  // Morning in the east, evening in the west; at midnight below the horizon.
  EXPECT_LT(solar_position(2026, 6, 21, 8, 1, 51.4769, 0).azimuth_degrees, 180);
  EXPECT_GT(solar_position(2026, 6, 21, 18, 1, 51.4769, 0).azimuth_degrees, 180);
  EXPECT_LT(solar_position(2026, 12, 21, 0, 0, 51.4769, 0).elevation_degrees, -50);
  EXPECT_EQ(day_of_year(2026, 1, 1), 1);
  EXPECT_EQ(day_of_year(2024, 12, 31), 366);
  EXPECT_EQ(day_of_year(2026, 3, 1), 60);
  EXPECT_EQ(day_of_year(2026, 2, 29), 0);
  EXPECT_EQ(day_of_year(2026, 13, 1), 0);
}

}  // namespace
}  // namespace candela
