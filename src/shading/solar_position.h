// Where the sun is: the Astronomical Almanac's approximate algorithm as
// Michalsky published it (Solar Energy 40:227, 1988; ±0.01° from 1950 to 2050), with the azimuth
// by atan2 (Michalsky's arcsine needed Spencer's 1989 quadrant correction) and his refraction
// correction near the horizon.
#pragma once

namespace candela {

struct SolarPosition {
  double elevation_degrees = 0;  // above the horizon, refraction included
  double azimuth_degrees = 0;    // from north, clockwise (east 90°)
};

// A civil date and time at a place: latitude north and longitude east in degrees, local time
// `hours` (0 to 24, decimal) in a zone `timezone_hours` ahead of UT (Central Europe +1, Denver −7).
SolarPosition solar_position(int year, int month, int day, double hours, double timezone_hours,
                             double latitude, double longitude);

// The day of the year (1 January = 1) of a Gregorian date; 0 for a date that does not exist.
int day_of_year(int year, int month, int day);

}  // namespace candela
