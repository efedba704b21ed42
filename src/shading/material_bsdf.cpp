#include "shading/material_bsdf.h"

#include <cmath>

#include "shading/bump.h"
#include "shading/fresnel.h"

namespace candela {

Bsdf make_bsdf(const Material& material, const SurfaceProperties& at, const SurfaceHit& hit,
               const Vec3& shading_normal) {
  const Vec3& geometric = hit.geometric_normal;
  const Vec3 normal = dot(shading_normal, geometric) < 0 ? -shading_normal : shading_normal;
  // A smooth mesh's facets are not the surface (Hanika 2021): its shading normal says which side a
  // direction is on, and rays leave from SurfaceHit::lifted_toward.
  Bsdf bsdf(ShadingFrame::from_normal(normal), geometric, hit.interpolated_normal);

  // glTF 2.0's metallic-roughness BRDF, fresnel_mix(diffuse, specular): the diffuse beneath the
  // facets has 1 − F (BsdfLobe::beneath_facets), and the facets' own F bounds them, so they are
  // added after the energy rule.
  const bool layered =
      material.layered && material.specular_model == SpecularModel::cook_torrance && at.ks > 0;
  BsdfLobe diffuse;
  diffuse.type = LobeType::lambert;
  diffuse.weight = at.diffuse_albedo();
  if (layered) {
    diffuse.beneath_facets = true;
    diffuse.fresnel = material.fresnel;
  }
  bsdf.add(diffuse);

  BsdfLobe specular;
  specular.weight = Color(at.ks);
  if (material.specular_model == SpecularModel::cook_torrance) {
    specular.type = LobeType::microfacet;
    specular.alpha = at.roughness;
    specular.distribution = material.microfacet;
    specular.fresnel = material.fresnel;
  } else {
    // Phong and Blinn-Phong both become the normalized Phong lobe about the mirror
    // direction, with the material's exponent as given.
    specular.type = LobeType::phong;
    specular.exponent = at.shininess;
  }
  if (at.ks > 0 && !layered) bsdf.add(specular);
  if (at.kr > 0) {
    BsdfLobe mirror;
    mirror.type = LobeType::mirror;
    mirror.weight = Color(at.kr);
    bsdf.add(mirror);
  }
  if (at.kt > 0) {
    BsdfLobe glass;
    glass.type = material.thin ? LobeType::thin_dielectric : LobeType::dielectric;
    glass.weight = Color(at.kt);
    glass.ior = at.ior;
    bsdf.add(glass);
  }
  bsdf.conserve_energy();
  if (layered) bsdf.add(specular);
  return bsdf;
}

Color thin_sheet_transmittance(const Material& material, const SurfaceHit& hit, const Vec3& direction) {
  if (!(material.thin && material.has_refraction())) return {};
  SurfaceHit shading = hit;
  shading.shading_normal = bumped_normal(material.bump, hit);  // 000 §4.2.1: the bump tilts it
  const Bsdf bsdf = make_bsdf(material, material.at(shading), shading, shading.shading_normal);
  const double cos_theta = std::fabs(dot(bsdf.frame().n, direction));
  Color through;
  for (int i = 0; i < bsdf.lobe_count(); ++i)
    if (bsdf.lobe(i).type == LobeType::thin_dielectric)
      through += thin_sheet(cos_theta, bsdf.lobe(i).ior, bsdf.lobe(i).weight).transmittance;
  return through;
}

}  // namespace candela
