// Textures give a value at a surface point (SPEC §7); created by name (scene/material_registry).
// Color parameters read evaluate(); scalar parameters (ks, n, kr, kt, ior, roughness, bump
// heights) read evaluate_scalar(), the mean of the three channels.
#pragma once

#include <memory>
#include <string_view>

#include "geometry/surface_hit.h"
#include "math/vector.h"
#include "shading/texture_mapping.h"

namespace candela {

class Texture {
 public:
  virtual ~Texture() = default;
  virtual Color evaluate(const SurfaceHit& hit) const = 0;
  double evaluate_scalar(const SurfaceHit& hit) const {
    const Color c = evaluate(hit);
    return (c.r + c.g + c.b) / 3;
  }
  virtual std::string_view type_name() const = 0;
  // True when evaluate() is the same everywhere (lets the loader check kr + kt <= 1 up front).
  virtual bool is_constant() const { return false; }
};

class ConstantTexture final : public Texture {
 public:
  explicit ConstantTexture(const Color& value) : value_(value) {}
  Color evaluate(const SurfaceHit&) const override { return value_; }
  std::string_view type_name() const override { return "constant"; }
  bool is_constant() const override { return true; }
  const Color& value() const { return value_; }

 private:
  Color value_;
};

// A texture defined over a 2D (u, v) domain, reached from the hit through a mapping (the
// shape's own uv, spherical, planar, cylindrical; see texture_mapping.h).
class Texture2D : public Texture {
 public:
  explicit Texture2D(std::shared_ptr<const TextureMapping> mapping) : mapping_(std::move(mapping)) {}
  Color evaluate(const SurfaceHit& hit) const final { return lookup(mapping_->map(hit)); }
  virtual Color lookup(const Vec2& uv) const = 0;
  const TextureMapping& mapping() const { return *mapping_; }

 private:
  std::shared_ptr<const TextureMapping> mapping_;
};

// A solid (3D) texture over the shape's own coordinates (SurfaceHit::object_position), so it
// moves with the object's transform; `texture_from_object` places, turns and scales it.
class SolidTexture : public Texture {
 public:
  explicit SolidTexture(const Transform& texture_from_object = {})
      : texture_from_object_(texture_from_object), identity_(texture_from_object.is_identity()) {}
  Color evaluate(const SurfaceHit& hit) const final {
    return at(identity_ ? hit.object_position : texture_from_object_.point(hit.object_position));
  }
  virtual Color at(const Vec3& p) const = 0;

 private:
  Transform texture_from_object_;
  bool identity_;
};

}  // namespace candela
