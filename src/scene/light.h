// Light sources of the local model (SPEC §7). Ambient light is a scene-wide color.
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
  // False when the point receives nothing (outside a spot cone). A light made of many points
  // (an area light) answers here as one point at its centre carrying all of it; methods that
  // trace shadows use the samples below instead.
  virtual bool illuminate(const Vec3& point, LightSample& sample) const = 0;
  virtual std::string_view type_name() const = 0;

  // The light as sample_count() point samples whose intensities add up to what it sends: one for
  // the point-like lights, a fixed stratified set for an area light (the same for every point,
  // so images do not depend on anything but the point).
  virtual int sample_count() const { return 1; }
  virtual bool illuminate_sample(const Vec3& point, int index, LightSample& sample) const {
    return index == 0 && illuminate(point, sample);
  }
  // One random point of the light (u uniform in [0, 1)²) carrying the whole light, so that its
  // expectation over u is what the sample_count() samples give together: the path tracer's
  // next-event estimate (SPEC §12). Point-like lights answer with their one sample.
  virtual bool illuminate_random(const Vec3& point, const Vec2& u, LightSample& sample) const {
    (void)u;
    return illuminate(point, sample);
  }
};

}  // namespace candela
