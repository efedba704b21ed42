#include "shading/local_model.h"

#include <cmath>

#include "shading/optics.h"

namespace candela {

Color direct_term(const Material& material, const Color& kd, const Vec3& N, const Vec3& V,
                  const Vec3& L, const Color& light_intensity) {
  const double n_dot_l = dot(N, L);
  if (n_dot_l <= 0) return {};
  double specular = 0;
  if (material.ks > 0) {
    double cosine;
    if (material.specular_model == SpecularModel::phong) {
      cosine = dot(reflect(L, N), V);  // R_i·V: L mirrored about N
    } else {
      const Vec3 half = L + V;
      const double half_length = length(half);
      cosine = half_length > 0 ? dot(N, half / half_length) : 0;
    }
    if (cosine > 0) specular = material.ks * std::pow(cosine, material.shininess);
  }
  return light_intensity * (kd * n_dot_l + Color(specular));
}

}  // namespace candela
