// An image on a surface (SPEC §7: image textures, bilinear): the mapping gives (u, v), the
// image is read bilinearly with a wrap mode and scaled by a multiplier.
#pragma once

#include <memory>

#include "shading/texture.h"
#include "shading/texture_image.h"

namespace candela {

class ImageTexture final : public Texture2D {
 public:
  // Throws std::invalid_argument for a null image or mapping.
  ImageTexture(std::shared_ptr<const TextureImage> image, WrapMode wrap, const Color& multiplier,
               std::shared_ptr<const TextureMapping> mapping);

  // multiplier · image.bilinear(uv, wrap); (u, v) as TextureImage: v = 0 at the bottom row.
  Color lookup(const Vec2& uv) const override { return multiplier_ * image_->bilinear(uv, wrap_); }
  std::string_view type_name() const override { return "image"; }

  const TextureImage& image() const { return *image_; }
  WrapMode wrap() const { return wrap_; }
  const Color& multiplier() const { return multiplier_; }

 private:
  std::shared_ptr<const TextureImage> image_;
  WrapMode wrap_;
  Color multiplier_;
};

}  // namespace candela
