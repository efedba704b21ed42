#include "shading/local_model.h"

#include <cmath>

#include "shading/cook_torrance.h"
#include "shading/optics.h"

namespace candela {

Color direct_term(const Material& material, const SurfaceProperties& at, const Vec3& N, const Vec3& V,
                  const Vec3& L, const Color& light_intensity) {
  const double n_dot_l = dot(N, L);
  if (n_dot_l <= 0) return {};
  Color specular;
  if (at.ks > 0) {
    if (material.specular_model == SpecularModel::cook_torrance) {
      specular = at.ks * n_dot_l * cook_torrance(N, V, L, at.roughness, material.fresnel);
    } else {
      double cosine;
      if (material.specular_model == SpecularModel::phong) {
        cosine = dot(reflect(L, N), V);  // R_i·V: L mirrored about N
      } else {
        const Vec3 half = L + V;
        const double half_length = length(half);
        cosine = half_length > 0 ? dot(N, half / half_length) : 0;
      }
      if (cosine > 0) specular = Color(at.ks * std::pow(cosine, at.shininess));
    }
  }
  return light_intensity * (at.kd * n_dot_l + specular);
}

}  // namespace candela
