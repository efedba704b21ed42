#pragma once

#include "math/constants.h"
#include "math/direction.h"
#include "sampling/warps.h"
#include "scene/light.h"

namespace candela {

// A source at infinity (000 §2.3): the same direction and intensity everywhere — or, given an
// angular diameter (the sun's 0.53°), the same intensity spread evenly over a
// disc of directions of that size about it: soft shadows, penumbrae as wide as the disc. The disc
// is sampled uniformly in solid angle (samples × samples strata for the methods that take a light's
// fixed samples; one random direction for the path tracer); no ray can hit it.
class DirectionalLight final : public Light {
 public:
  // direction: the way the light travels; L is its opposite. type_name: "directional", or "sun"
  // for the one placed by a date and a place (scene/light_registry.cpp). angular_diameter in
  // radians (0: one direction), samples per side of its strata.
  DirectionalLight(const Vec3& direction, const Color& intensity, std::string_view type_name = "directional",
                   double angular_diameter = 0, int samples = 1)
      : to_light_(-direction_of(direction).value_or(Vec3{})),
        intensity_(intensity),
        type_name_(type_name),
        cos_max_(std::cos(angular_diameter / 2)),
        disc_(angular_diameter > 0),
        samples_(angular_diameter > 0 ? std::max(1, samples) : 1) {
    orthonormal_basis(to_light_, across_u_, across_v_);
  }
  bool illuminate(const Vec3&, LightSample& sample) const override {
    sample = {to_light_, kInfinity, intensity_};
    return true;
  }
  int sample_count() const override { return samples_ * samples_; }
  bool stratified() const override { return disc_; }  // the disc's samples move in their cells
  bool illuminate_sample(const Vec3&, int index, const Vec2& within, LightSample& sample) const override {
    if (!disc_) return index == 0 && illuminate({}, sample);
    sample = {toward(stratum_point(index, samples_, within)), kInfinity,
              intensity_ / double(samples_ * samples_)};
    return true;
  }
  bool illuminate_random(const Vec3&, const Vec2& u, LightSample& sample) const override {
    sample = {disc_ ? toward(u) : to_light_, kInfinity, intensity_};
    return true;
  }
  std::string_view type_name() const override { return type_name_; }
  // The flux through the scene's disc across the beam, π r² · I.
  Color power(double scene_radius) const override { return intensity_ * (kPi * scene_radius * scene_radius); }

 private:
  // The direction of u ∈ [0, 1)² in the disc.
  Vec3 toward(const Vec2& u) const {
    const Vec3 local = square_to_uniform_cone(u, cos_max_);
    return normalize(across_u_ * local.x + across_v_ * local.y + to_light_ * local.z);
  }
  Vec3 to_light_;
  Color intensity_;
  std::string_view type_name_;  // a literal
  double cos_max_;              // of the disc's half-angle
  bool disc_;                   // a disc of directions (else the one direction)
  int samples_;
  Vec3 across_u_, across_v_;
};

}  // namespace candela
