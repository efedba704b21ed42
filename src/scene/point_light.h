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
  const Vec3& position() const { return position_; }

 private:
  Vec3 position_;
  Color intensity_;
  Attenuation attenuation_;
};

}  // namespace candela
