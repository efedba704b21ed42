#include "shading/solar_position.h"

#include <cmath>

#include "math/constants.h"

namespace candela {

namespace {

constexpr double kDegrees = 180 / kPi;

double wrap(double value, double period) {
  value = std::fmod(value, period);
  return value < 0 ? value + period : value;
}

bool leap_year(int year) {
  return (year % 4 == 0 && year % 100 != 0) || year % 400 == 0;
}

}  // namespace

int day_of_year(int year, int month, int day) {
  static constexpr int kDays[12] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  if (month < 1 || month > 12 || day < 1) return 0;
  const int length = kDays[month - 1] + (month == 2 && leap_year(year) ? 1 : 0);
  if (day > length) return 0;
  int count = day;
  for (int m = 1; m < month; ++m) count += kDays[m - 1] + (m == 2 && leap_year(year) ? 1 : 0);
  return count;
}

SolarPosition solar_position(int year, int month, int day, double hours, double timezone_hours,
                             double latitude, double longitude) {
  // Universal time; the day moves with it.
  double ut = hours - timezone_hours;
  int day_number = day_of_year(year, month, day);
  while (ut < 0) {
    ut += 24;
    --day_number;
  }
  while (ut >= 24) {
    ut -= 24;
    ++day_number;
  }
  // Michalsky 1988: the Julian date from 1949's, then the ecliptic coordinates.
  const int delta = year - 1949;
  const int leap = static_cast<int>(std::floor(delta / 4.0));
  const double julian = 2432916.5 + delta * 365.0 + leap + day_number + ut / 24;
  const double time = julian - 2451545.0;
  const double mean_longitude = wrap(280.460 + 0.9856474 * time, 360);
  const double mean_anomaly = wrap(357.528 + 0.9856003 * time, 360) / kDegrees;
  const double ecliptic_longitude =
      wrap(mean_longitude + 1.915 * std::sin(mean_anomaly) + 0.020 * std::sin(2 * mean_anomaly), 360) /
      kDegrees;
  const double obliquity = (23.439 - 0.0000004 * time) / kDegrees;
  const double right_ascension =
      std::atan2(std::cos(obliquity) * std::sin(ecliptic_longitude), std::cos(ecliptic_longitude));
  const double declination = std::asin(std::sin(obliquity) * std::sin(ecliptic_longitude));
  // Sidereal time and the hour angle.
  const double greenwich = wrap(6.697375 + 0.0657098242 * time + ut, 24);
  const double local = wrap(greenwich + longitude / 15, 24) * 15 / kDegrees;
  double hour_angle = local - right_ascension;
  hour_angle = std::remainder(hour_angle, 2 * kPi);
  const double phi = latitude / kDegrees;
  const double elevation = std::asin(std::sin(declination) * std::sin(phi) +
                                     std::cos(declination) * std::cos(phi) * std::cos(hour_angle));
  const double azimuth = std::atan2(
      -std::sin(hour_angle) * std::cos(declination),
      std::sin(declination) * std::cos(phi) - std::cos(declination) * std::sin(phi) * std::cos(hour_angle));
  SolarPosition position;
  double elevation_degrees = elevation * kDegrees;
  // Refraction (Michalsky's fit, degrees), 0.56° below the horizon.
  const double refraction =
      elevation_degrees > -0.56
          ? 3.51561 *
                (0.1594 + 0.0196 * elevation_degrees + 0.00002 * elevation_degrees * elevation_degrees) /
                (1 + 0.505 * elevation_degrees + 0.0845 * elevation_degrees * elevation_degrees)
          : 0.56;
  if (elevation_degrees + refraction <= 90) elevation_degrees += refraction;
  position.elevation_degrees = elevation_degrees;
  position.azimuth_degrees = wrap(azimuth * kDegrees, 360);
  return position;
}

}  // namespace candela
