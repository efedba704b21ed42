// Textures give a colour at a surface point (SPEC §7); created by name (scene/texture_registry).
#pragma once

#include <string_view>

#include "geometry/surface_hit.h"
#include "math/vector.h"

namespace candela {

class Texture {
 public:
  virtual ~Texture() = default;
  virtual Color evaluate(const SurfaceHit& hit) const = 0;
  virtual std::string_view type_name() const = 0;
};

class ConstantTexture final : public Texture {
 public:
  explicit ConstantTexture(const Color& value) : value_(value) {}
  Color evaluate(const SurfaceHit&) const override { return value_; }
  std::string_view type_name() const override { return "constant"; }
  const Color& value() const { return value_; }

 private:
  Color value_;
};

}  // namespace candela
