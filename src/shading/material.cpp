#include "shading/material.h"

#include <algorithm>
#include <cmath>

namespace candela {

namespace {

bool is_constant_zero(const std::shared_ptr<const Texture>& texture) {
  const auto* constant = dynamic_cast<const ConstantTexture*>(texture.get());
  return constant && constant->value().is_black();
}

// Textures may give anything (noise and waves go negative, a float image may hold anything):
// reflectances are kept >= 0 and NaN reads as 0, so no pixel turns negative or NaN.
double at_least_zero(double value) {
  return value > 0 ? value : 0.0;
}
Color at_least_zero(const Color& c) {
  return {at_least_zero(c.r), at_least_zero(c.g), at_least_zero(c.b)};
}
double in_unit_interval(double value) {
  return value > 0 ? std::min(value, 1.0) : 0.0;
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
    case TransparencyModel::none:
      return 0;
    case TransparencyModel::constant:
      return t_min;
    case TransparencyModel::linear:
      return t_min + (t_max - t_min) * n_z;  // 000 §4.4
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
  if (constant_) return constant_properties_;
  SurfaceProperties p;
  p.kd = at_least_zero(kd->evaluate(hit));
  p.ka = ka ? at_least_zero(ka->evaluate(hit)) : p.kd;
  p.ks = at_least_zero(ks->evaluate_scalar(hit));
  p.shininess = at_least_zero(shininess->evaluate_scalar(hit));
  p.roughness = std::max(1e-4, at_least_zero(roughness->evaluate_scalar(hit)));
  p.kr = in_unit_interval(kr->evaluate_scalar(hit));
  p.kt = in_unit_interval(kt->evaluate_scalar(hit));
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

double Material::transmission_at(const SurfaceHit& hit) const {
  const double transmission = in_unit_interval(kt->evaluate_scalar(hit));
  if (!reflects_) return transmission;
  // As in at(): where kr + kt > 1 both shrink in proportion.
  const double reflection = in_unit_interval(kr->evaluate_scalar(hit));
  return reflection + transmission > 1 ? transmission / (reflection + transmission) : transmission;
}

void Material::prepare() {
  reflects_ = !is_constant_zero(kr);
  refracts_ = !is_constant_zero(kt);
  constant_ = false;
  bool constant = true;
  for (const auto* texture : {&kd, &ks, &shininess, &roughness, &kr, &kt, &ior})
    constant = constant && *texture && (*texture)->is_constant();
  constant = constant && (!ka || ka->is_constant());
  if (constant) {
    constant_properties_ = at(SurfaceHit{});
    constant_ = true;
  }
}

}  // namespace candela
