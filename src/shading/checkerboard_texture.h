#pragma once

#include "shading/texture.h"

namespace candela {

// A solid (3D) checkerboard over the shape's own coordinates: cells of edge `size`, colour
// `even` where floor(x/size) + floor(y/size) + floor(z/size) is even (000 Figure 49's floor).
class CheckerboardTexture final : public Texture {
 public:
  CheckerboardTexture(const Color& even, const Color& odd, double size, const Vec3& offset);
  Color evaluate(const SurfaceHit& hit) const override;
  std::string_view type_name() const override { return "checkerboard"; }

 private:
  Color even_, odd_;
  double inverse_size_;
  Vec3 offset_;
};

}  // namespace candela
