// Where a scene file puts the sun (the sun light and the CIE sky read it):
// "latitude" (° north), "longitude" (° east), "date" ("YYYY-MM-DD"), "time" (local
// "HH:MM[:SS]") and "timezone" (hours ahead of UT), by Michalsky's algorithm
// (shading/solar_position.h); or, for the sky, without a date, "sun_elevation" and "sun_azimuth"
// (degrees, azimuth from north clockwise; default 45 and 180) given directly. "north" (default −z) orients
// the compass: y is up, east is north × up.
#pragma once

#include "io/json_node.h"
#include "math/vector.h"
#include "shading/solar_position.h"

namespace candela {

struct SunPlacement {
  SolarPosition position;
  Vec3 toward_sun;   // unit, in the scene's frame
  Vec3 north, east;  // unit, horizontal
};

// allow_angles: sun_elevation / sun_azimuth may stand for the place and time.
SunPlacement read_sun_placement(const JsonNode& node, bool allow_angles);

}  // namespace candela
