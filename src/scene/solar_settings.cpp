#include "scene/solar_settings.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "math/constants.h"

namespace candela {

namespace {

// The years Michalsky's almanac is used for here: its ±0.01° holds 1950–2050 and degrades slowly
// outside; beyond 1900–2100 a date is refused rather than placed wrongly.
constexpr int kFirstYear = 1900, kLastYear = 2100;

// The number of the `count` digits at text[at...]; -1 unless they are all digits
// (sscanf's %d took signs, blanks and anything after the last field: "2026-+6-21", "12:00 tomorrow").
int digits_at(const std::string& text, std::size_t at, std::size_t count) {
  if (at + count > text.size()) return -1;
  int value = 0;
  for (std::size_t i = at; i < at + count; ++i) {
    if (text[i] < '0' || text[i] > '9') return -1;
    value = 10 * value + (text[i] - '0');
  }
  return value;
}

// YYYY-MM-DD exactly (ISO 8601's calendar date).
bool read_date(const std::string& text, int& year, int& month, int& day) {
  if (text.size() != 10 || text[4] != '-' || text[7] != '-') return false;
  year = digits_at(text, 0, 4);
  month = digits_at(text, 5, 2);
  day = digits_at(text, 8, 2);
  return year >= kFirstYear && year <= kLastYear && month >= 1 && day >= 1 &&
         day_of_year(year, month, day) > 0;
}

// HH:MM or HH:MM:SS (the hour may have one digit), seconds with an optional fraction; up to 24:00.
bool read_time(const std::string& text, double& hours) {
  const std::size_t colon = text.find(':');
  if (colon != 1 && colon != 2) return false;
  const int h = digits_at(text, 0, colon), m = digits_at(text, colon + 1, 2);
  double seconds = 0;
  std::size_t end = colon + 3;
  if (end < text.size()) {
    if (text[end] != ':') return false;
    const int whole = digits_at(text, end + 1, 2);
    if (whole < 0 || whole > 59) return false;
    seconds = whole;
    end += 3;
    if (end < text.size()) {
      if (text[end] != '.' || end + 1 == text.size()) return false;
      double scale = 0.1;
      for (std::size_t i = end + 1; i < text.size(); ++i, scale /= 10) {
        if (text[i] < '0' || text[i] > '9') return false;
        seconds += (text[i] - '0') * scale;
      }
      // 59.999… of many digits may round up to 60 in the sum: it is still within the minute.
      seconds = std::min(seconds, std::nextafter(60.0, 0.0));
    }
  }
  if (h < 0 || h > 24 || m < 0 || m > 59) return false;
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
