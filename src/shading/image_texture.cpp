#include "shading/image_texture.h"

#include <stdexcept>

namespace candela {

namespace {
// Checked before Texture2D stores the mapping, so that a null one never reaches evaluate().
std::shared_ptr<const TextureMapping> non_null(std::shared_ptr<const TextureMapping> mapping) {
  if (!mapping) throw std::invalid_argument("ImageTexture needs a texture mapping");
  return mapping;
}
}  // namespace

ImageTexture::ImageTexture(std::shared_ptr<const TextureImage> image, WrapMode wrap, const Color& multiplier,
                           std::shared_ptr<const TextureMapping> mapping)
    : Texture2D(non_null(std::move(mapping))),
      image_(std::move(image)),
      wrap_(wrap),
      multiplier_(multiplier) {
  if (!image_) throw std::invalid_argument("ImageTexture needs an image");
}

}  // namespace candela
