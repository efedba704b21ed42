#pragma once

#include "math/transform.h"
#include "shading/texture.h"

namespace candela {

// A solid (3D) checkerboard over the shape's own coordinates (000 Figure 49's floor): cells of
// edge `size`, color `even` where floor(q.x/size) + floor(q.y/size) + floor(q.z/size) is even,
// with q = texture_from_object(object position) + offset. A bias of 1e-9 cell is added before the
// floor so that points lying exactly on a cell face (a floor at y = 0) all fall on one side
// instead of flickering between the two colors with rounding.
class CheckerboardTexture final : public SolidTexture {
 public:
  // Cells shifted by `offset` (in object units): q = object position + offset.
  CheckerboardTexture(const Color& even, const Color& odd, double size, const Vec3& offset);
  // Cells placed, turned and scaled by a transform: q = texture_from_object(object position).
  CheckerboardTexture(const Color& even, const Color& odd, double size, const Transform& texture_from_object);
  Color at(const Vec3& p) const override;
  std::string_view type_name() const override { return "checkerboard"; }

 private:
  Color even_, odd_;
  double inverse_size_;
  Vec3 offset_;
};

}  // namespace candela
