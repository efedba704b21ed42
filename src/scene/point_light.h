#pragma once

#include "scene/attenuation.h"
#include "scene/light.h"

namespace candela {

class PointLight final : public Light {
 public:
  PointLight(const Vec3& position, const Color& intensity, const Attenuation& attenuation)
      : position_(position), intensity_(intensity), attenuation_(attenuation) {}
  bool illuminate(const Vec3& point, LightSample& sample) const override;
  std::string_view type_name() const override { return "point"; }
  // 4π r² · I · f_at(r): the flux through the sphere of radius r around it (I for 1/(4π d²)).
  Color power(double scene_radius) const override {
    return intensity_ * (attenuation_.factor(scene_radius) * 4 * kPi * scene_radius * scene_radius);
  }
  const Vec3& position() const { return position_; }

 private:
  Vec3 position_;
  Color intensity_;
  Attenuation attenuation_;
};

}  // namespace candela
