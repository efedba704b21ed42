// Light sources of the local model (SPEC §7). Ambient light is a scene-wide colour.
#pragma once

#include <string_view>

#include "math/vector.h"

namespace candela {

// Light arriving at a point from one source, before shadowing.
struct LightSample {
  Vec3 direction;   // L: unit, from the point toward the light
  double distance;  // to the light; infinity for a directional light
  Color intensity;  // Ip · f_at (· spot factor)
};

class Light {
 public:
  virtual ~Light() = default;
  // False when the point receives nothing (outside a spot cone).
  virtual bool illuminate(const Vec3& point, LightSample& sample) const = 0;
  virtual std::string_view type_name() const = 0;
};

}  // namespace candela
