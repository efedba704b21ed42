#include "shading/checkerboard_texture.h"

#include <cmath>
#include <stdexcept>

namespace candela {

CheckerboardTexture::CheckerboardTexture(const Color& even, const Color& odd, double size,
                                         const Vec3& offset)
    : even_(even), odd_(odd), inverse_size_(1.0 / size), offset_(offset) {
  if (!(size > 0)) throw std::invalid_argument("size must be > 0");
}

Color CheckerboardTexture::evaluate(const SurfaceHit& hit) const {
  // A tiny bias keeps points lying exactly on a cell face (a floor at y = 0) on one side.
  const Vec3 p = (hit.object_position + offset_) * inverse_size_ + Vec3{1e-9, 1e-9, 1e-9};
  const auto cell = static_cast<long long>(std::floor(p.x)) +
                    static_cast<long long>(std::floor(p.y)) +
                    static_cast<long long>(std::floor(p.z));
  return (cell & 1) ? odd_ : even_;
}

}  // namespace candela
