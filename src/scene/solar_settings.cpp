#include "scene/solar_settings.h"

#include <fmt/format.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "math/constants.h"

namespace candela {

namespace {

// The years Michalsky's almanac is used for here: its ±0.01° holds 1950–2050 and degrades slowly
// outside; beyond 1900–2100 a date is refused rather than placed wrongly.
constexpr int kFirstYear = 1900, kLastYear = 2100;

bool read_date(const std::string& text, int& year, int& month, int& day) {
  return text.size() == 10 && std::sscanf(text.c_str(), "%d-%d-%d", &year, &month, &day) == 3 &&
         year >= kFirstYear && year <= kLastYear && day_of_year(year, month, day) > 0;
}

bool read_time(const std::string& text, double& hours) {
  int h = 0, m = 0;
  double seconds = 0;
  const int parts = std::sscanf(text.c_str(), "%d:%d:%lf", &h, &m, &seconds);
  if (parts < 2 || h < 0 || h > 24 || m < 0 || m > 59 || seconds < 0 || seconds >= 60) return false;
  hours = h + m / 60.0 + seconds / 3600;
  return hours <= 24;
}

}  // namespace

SunPlacement read_sun_placement(const JsonNode& node, bool allow_angles) {
  SunPlacement placement;
  Vec3 north = node.vec3("north", Vec3{0, 0, -1});
  north.y = 0;
  if (!(length(north) > 0)) node.at("north").fail("must have a horizontal part (y is up)");
  placement.north = normalize(north);
  placement.east = cross(placement.north, Vec3{0, 1, 0});
  if (allow_angles && !node.json().contains("date")) {
    placement.position.elevation_degrees = node.number("sun_elevation", 45, {-90, 90, false, false});
    placement.position.azimuth_degrees = node.number("sun_azimuth", 180, {-360, 360, false, false});
  } else {
    const double latitude = node.number("latitude", 0, {-90, 90, false, false});
    const double longitude = node.number("longitude", 0, {-180, 180, false, false});
    int year = 0, month = 0, day = 0;
    const JsonNode date = node.at("date");
    if (!read_date(date.as_string(), year, month, day))
      date.fail(fmt::format("expected a date YYYY-MM-DD of the years {}–{}", kFirstYear, kLastYear));
    double hours = 12;
    const JsonNode time = node.at("time");
    if (!read_time(time.as_string(), hours)) time.fail("expected a local time HH:MM or HH:MM:SS");
    const double timezone = node.number("timezone", 0, {-14, 14, false, false});
    placement.position = solar_position(year, month, day, hours, timezone, latitude, longitude);
  }
  const double elevation = placement.position.elevation_degrees * kPi / 180;
  const double azimuth = placement.position.azimuth_degrees * kPi / 180;
  placement.toward_sun = placement.north * (std::cos(elevation) * std::cos(azimuth)) +
                         placement.east * (std::cos(elevation) * std::sin(azimuth)) +
                         Vec3{0, 1, 0} * std::sin(elevation);
  return placement;
}

}  // namespace candela
