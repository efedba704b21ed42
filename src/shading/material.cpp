#include "shading/material.h"

#include <algorithm>
#include <cmath>

namespace candela {

namespace {

bool is_constant_zero(const std::shared_ptr<const Texture>& texture) {
  const auto* constant = dynamic_cast<const ConstantTexture*>(texture.get());
  return constant && constant->value().is_black();
}

}  // namespace

std::shared_ptr<const Texture> constant_texture(double value) {
  return std::make_shared<ConstantTexture>(Color(value));
}
std::shared_ptr<const Texture> constant_texture(const Color& value) {
  return std::make_shared<ConstantTexture>(value);
}

double Transparency::at(double n_z) const {
  n_z = std::clamp(n_z, 0.0, 1.0);
  switch (model) {
    case TransparencyModel::none: return 0;
    case TransparencyModel::constant: return t_min;
    case TransparencyModel::linear: return t_min + (t_max - t_min) * n_z;  // 000 §4.4
    case TransparencyModel::nonlinear:
      return t_min + (t_max - t_min) * (1 - std::pow(1 - n_z, exponent));  // 000 §4.4
  }
  return 0;
}

Material::Material()
    : kd(constant_texture(0.8)),
      ks(constant_texture(0.0)),
      shininess(constant_texture(1.0)),
      roughness(constant_texture(0.3)),
      kr(constant_texture(0.0)),
      kt(constant_texture(0.0)),
      ior(constant_texture(1.0)) {}

SurfaceProperties Material::at(const SurfaceHit& hit) const {
  SurfaceProperties p;
  p.kd = kd->evaluate(hit);
  p.ka = ka ? ka->evaluate(hit) : p.kd;
  p.ks = std::max(0.0, ks->evaluate_scalar(hit));
  p.shininess = std::max(0.0, shininess->evaluate_scalar(hit));
  p.roughness = std::max(1e-4, roughness->evaluate_scalar(hit));
  p.kr = std::clamp(kr->evaluate_scalar(hit), 0.0, 1.0);
  p.kt = std::clamp(kt->evaluate_scalar(hit), 0.0, 1.0);
  // A textured kr + kt may exceed 1 somewhere; each level of the ray tree must carry less
  // than its parent, so both shrink in proportion there (constant ones are checked on load).
  if (p.kr + p.kt > 1) {
    const double total = p.kr + p.kt;
    p.kr /= total;
    p.kt /= total;
  }
  p.ior = ior->evaluate_scalar(hit);
  if (!(p.ior > 0)) p.ior = 1;
  return p;
}

double Material::transmission_at(const SurfaceHit& hit) const { return at(hit).kt; }

bool Material::has_reflection() const { return !is_constant_zero(kr); }
bool Material::has_refraction() const { return !is_constant_zero(kt); }
bool Material::lets_light_through() const { return has_refraction() || transparency.active(); }

}  // namespace candela
