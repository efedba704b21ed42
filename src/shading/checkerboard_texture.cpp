#include "shading/checkerboard_texture.h"

#include <cmath>
#include <stdexcept>

#include "shading/procedural_textures.h"

namespace candela {

namespace {

void validate(const Color& even, const Color& odd, double size) {
  if (!(std::isfinite(size) && size > 0)) throw std::invalid_argument("size must be > 0");
  for (const Color& color : {even, odd})
    if (!(std::isfinite(color.r) && std::isfinite(color.g) && std::isfinite(color.b)))
      throw std::invalid_argument("checkerboard colors must have finite components");
}

}  // namespace

CheckerboardTexture::CheckerboardTexture(const Color& even, const Color& odd, double size, const Vec3& offset)
    : even_(even), odd_(odd), inverse_size_(1.0 / size), offset_(offset) {
  validate(even, odd, size);
  if (!is_finite(offset)) throw std::invalid_argument("offset must have finite components");
}

CheckerboardTexture::CheckerboardTexture(const Color& even, const Color& odd, double size,
                                         const Transform& texture_from_object)
    : SolidTexture(texture_from_object), even_(even), odd_(odd), inverse_size_(1.0 / size) {
  validate(even, odd, size);
}

Color CheckerboardTexture::at(const Vec3& p) const {
  // A tiny bias keeps points lying exactly on a cell face (a floor at y = 0) on one side.
  const Vec3 q = (p + offset_) * inverse_size_ + Vec3{1e-9, 1e-9, 1e-9};
  // The sum of the three floors is even exactly when an even number of them are odd
  // (floor_parity, unlike a cast to an integer, is defined for huge and NaN coordinates).
  const int parity = floor_parity(q.x) ^ floor_parity(q.y) ^ floor_parity(q.z);
  return parity ? odd_ : even_;
}

}  // namespace candela
