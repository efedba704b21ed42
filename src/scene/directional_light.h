#pragma once

#include "math/constants.h"
#include "math/direction.h"
#include "scene/light.h"

namespace candela {

// A source at infinity (000 §2.3): the same direction and intensity everywhere.
class DirectionalLight final : public Light {
 public:
  // direction: the way the light travels; L is its opposite. type_name: "directional", or "sun"
  // for the one placed by a date and a place (scene/light_registry.cpp).
  DirectionalLight(const Vec3& direction, const Color& intensity, std::string_view type_name = "directional")
      : to_light_(-direction_of(direction).value_or(Vec3{})), intensity_(intensity), type_name_(type_name) {}
  bool illuminate(const Vec3&, LightSample& sample) const override {
    sample = {to_light_, kInfinity, intensity_};
    return true;
  }
  std::string_view type_name() const override { return type_name_; }
  // The flux through the scene's disc across the beam, π r² · I.
  Color power(double scene_radius) const override { return intensity_ * (kPi * scene_radius * scene_radius); }

 private:
  Vec3 to_light_;
  Color intensity_;
  std::string_view type_name_;  // a literal
};

}  // namespace candela
