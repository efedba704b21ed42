#include "integrators/direct_lighting.h"

#include <cmath>
#include <unordered_map>

#include "scene/light_samples.h"
#include "shading/local_model.h"
#include "shading/material_bsdf.h"

namespace candela {

Color shadow_transmittance(const Scene& scene, const Vec3& origin, const Vec3& L, double distance,
                           TraceContext& context, int tree_parent) {
  ++context.counts.shadow;
  Ray ray{origin, L, 0.0, distance};
  // Nothing lets light through: the first thing on the segment blocks it, which the
  // accelerator's any-hit query answers without filling a hit (on the two-mirror scene 4.3 M of
  // a render's 6.7 M rays are these). The ray tree names the blocker, so it takes the loop below.
  if (!scene.lets_light_through() && !context.tree) return Color(scene.occluded(ray) ? 0.0 : 1.0);
  Color transmittance(1);
  // Absorbing objects the ray is inside: where it entered (0 when it started inside) and
  // their absorption.
  std::unordered_map<uint32_t, std::pair<double, Color>> entered_at;
  const auto absorb = [&](const Color& absorption, double inside) {
    for (int c = 0; c < 3; ++c) transmittance[c] *= std::exp(-absorption[c] * inside);
  };
  std::unordered_map<uint32_t, bool> counted;
  constexpr int kMaxCrossings = 256;  // never loop forever on pathological input
  std::string note;
  for (int crossing = 0;; ++crossing) {
    Intersection hit;
    if (!scene.intersect(ray, hit)) break;
    const Material& material = scene.material_of(hit);
    const uint32_t object = scene.primitives[hit.primitive].object;
    double passes = material.lets_light_through() && crossing < kMaxCrossings ? 1.0 : 0.0;
    if (passes > 0 && material.transparency.active())
      passes *= material.transparency.at(std::fabs(dot(hit.surface.shading_normal, L)));
    Color through(passes);
    if (passes > 0 && material.has_refraction()) {
      if (material.thin) {
        // A thin sheet at each crossing: its transmittance at the angle it is crossed, as every
        // method's shadow rays (Scene::transmittance).
        through *= thin_sheet_transmittance(material, hit.surface, L);
      } else if (!counted[object]) {
        // A solid's kt once for the two faces a ray crosses.
        counted[object] = true;
        through *= material.transmission_at(hit.surface);
      }
    }
    if (through.is_black()) {
      transmittance = Color(0);
      if (context.tree) note = "blocked by " + scene.objects[object].name;
      break;
    }
    transmittance *= through;
    if (!material.absorption.is_black()) {
      const bool entering = dot(L, hit.surface.geometric_normal) < 0;
      if (entering) {
        entered_at[object] = {hit.surface.t, material.absorption};
      } else {
        const auto found = entered_at.find(object);
        absorb(material.absorption, hit.surface.t - (found != entered_at.end() ? found->second.first : 0.0));
        if (found != entered_at.end()) entered_at.erase(found);
      }
    }
    if (context.tree) note += (note.empty() ? "through " : ", through ") + scene.objects[object].name;
    ray.t_min = hit.surface.t + scene.ray_offset(hit.surface.position);
    if (ray.t_min >= ray.t_max) break;
  }
  // A light inside an absorbing object: the path from the last entry to the light.
  if (std::isfinite(distance) && !transmittance.is_black())
    for (const auto& [object, entry] : entered_at) absorb(entry.second, distance - entry.first);
  if (context.tree) {
    RayTreeNode node;
    node.parent = tree_parent;
    node.kind = RayKind::shadow;
    if (tree_parent >= 0) {
      node.depth = context.tree->node(tree_parent).depth;
      node.weight = context.tree->node(tree_parent).weight;
    }
    node.origin = origin;
    node.direction = L;
    node.transmittance = transmittance;
    node.note = note.empty() ? "unobstructed" : note;
    context.tree->add(node);
  }
  return transmittance;
}

Color local_illumination(const Scene& scene, const Intersection& hit, const SurfaceProperties& at,
                         const Vec3& V, bool shadows, TraceContext& context, int tree_parent) {
  const Material& material = scene.material_of(hit);
  const SurfaceHit& surface = hit.surface;
  // Two-sided shading: the normals turned toward the viewer.
  const Vec3 N = face_forward(surface.shading_normal, V);
  const Vec3 geometric = face_forward(surface.geometric_normal, V);
  // A self-luminous surface shows its emitted exitance whatever lights it (000 eq. 6-7's E_i).
  Color result = at.ka * scene.ambient + material.emission;
  // A pure mirror or clear glass has no local diffuse or specular part: no shadow rays.
  if (at.kd.is_black() && at.ks <= 0) return result;
  const double offset = scene.ray_offset(surface.position);
  // A smooth mesh's shadow rays leave from Hanika's lifted point (SurfaceHit::lifted_toward).
  const Vec3 shadow_origin = surface.lifted_toward(V) + geometric * offset;
  // Every emitter — the lights and the emissive surfaces — each sample of an area light
  // or an emissive surface jittered within its cell per shading point (no stepped penumbrae).
  const StratumJitter jitter{true, context.seed};
  for (std::size_t e = 0; e < scene.emitter_count(); ++e) {
    const Light& light = scene.emitter(e);
    // Each of the light's samples (one, or an area light's samples²) with its own shadow ray.
    for_each_light_sample(
        light, e, surface.position, offset, jitter, [&](const LightSample& sample, double reach) {
          // 001's I_lum: only where N·L > 0; a light behind the surface itself casts no light on it —
          // behind the facet, unless the facet stands for a smooth surface whose shading normal faces
          // the light: then the shadow ray from the lifted point decides (no stepped terminator).
          if (dot(N, sample.direction) <= 0) return;
          if (dot(geometric, sample.direction) <= 0 && !(surface.interpolated_normal && shadows)) return;
          Color s(1);
          if (shadows) {
            s = shadow_transmittance(scene, shadow_origin, sample.direction, reach, context, tree_parent);
            if (s.is_black()) return;
          }
          result += direct_term(material, at, N, V, sample.direction, sample.intensity * s);
        });
  }
  return result;
}

}  // namespace candela
