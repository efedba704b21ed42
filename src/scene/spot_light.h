#pragma once

#include "scene/attenuation.h"
#include "scene/light.h"

namespace candela {

// A point light limited to a cone: full intensity inside falloff_start, zero outside
// cutoff, a smooth step between (pbrt's spot light), times (cos α)^exponent (Warn's model).
class SpotLight final : public Light {
 public:
  SpotLight(const Vec3& position, const Vec3& target, const Color& intensity, double cutoff_degrees,
            double falloff_start_degrees, double exponent, const Attenuation& attenuation);
  bool illuminate(const Vec3& point, LightSample& sample) const override;
  std::string_view type_name() const override { return "spot"; }
  // A point light's power times the part of the sphere its cone covers, the smooth step counted
  // half (pbrt's SpotLight::Phi); the (cos α)^exponent factor is left out.
  Color power(double scene_radius) const override;
  // The factor for a direction at angle alpha from the axis, given as cos(alpha).
  double cone_factor(double cos_alpha) const;
  // ∫ cone_factor dω over the sphere, in steradians: the flux of a unit intensity (the smooth
  // step and the exponent counted exactly, by a 4,096-step midpoint rule in cos α).
  double solid_angle() const;

 private:
  Vec3 position_;
  Vec3 axis_;
  Color intensity_;
  double cos_cutoff_;
  double cos_falloff_start_;
  double exponent_;
  Attenuation attenuation_;
};

}  // namespace candela
