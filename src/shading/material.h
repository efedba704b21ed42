// The classic material of the local model and Whitted ray tracing (SPEC §7, §8).
#pragma once

#include <memory>
#include <string>

#include "shading/texture.h"

namespace candela {

enum class SpecularModel { phong, blinn_phong };

struct Material {
  std::string name;
  std::shared_ptr<const Texture> kd;  // diffuse reflectance per channel (000 §2.9)
  Color ka;                            // ambient reflectance per channel
  bool ka_follows_kd = true;           // seed 000 eq. 5-2 uses kd·Ia: ka = kd unless given
  double ks = 0;                       // local specular, colourless (000 §2.9)
  double shininess = 1;                // n of (R·V)^n or (N·H)^n
  SpecularModel specular_model = SpecularModel::phong;
  double kr = 0;                       // global specular reflection (000 eq. 5-2)
  double kt = 0;                       // global specular transmission
  double ior = 1;                      // index of refraction (000 eq. 5-6)
  Color absorption;                    // per unit length inside: exp(-a·d) on shadow rays

  Color diffuse(const SurfaceHit& hit) const { return kd->evaluate(hit); }
  Color ambient(const SurfaceHit& hit) const { return ka_follows_kd ? diffuse(hit) : ka; }
};

}  // namespace candela
