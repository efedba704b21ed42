#include "integrators/whitted.h"

#include <cmath>
#include <string_view>

#include "integrators/direct_lighting.h"
#include "shading/bump.h"
#include "shading/fresnel.h"
#include "shading/optics.h"

namespace candela {

WhittedSettings read_whitted_settings(const JsonNode& node) {
  WhittedSettings settings;
  node.expect_object();
  settings.max_depth = node.integer("max_depth", settings.max_depth, {0, 64, false, false});
  settings.min_weight = node.number("min_weight", settings.min_weight, Range::unit());
  settings.shadows = node.boolean("shadows", settings.shadows);
  node.finish();
  return settings;
}

namespace {

Color trace(const Scene& scene, const Ray& ray, const TreeLimits& limits, RayKind kind, int depth,
            double weight, TraceContext& context, int tree_parent) {
  int node_index = -1;
  if (context.tree) {
    RayTreeNode node;
    node.parent = tree_parent;
    node.kind = kind;
    node.depth = depth;
    node.origin = ray.origin;
    node.direction = ray.direction;
    node.weight = weight;
    node_index = context.tree->add(node);
  }
  // Notes are string literals: nothing is allocated per ray unless a tree is recorded.
  const auto finish = [&](const Color& radiance, const Color& local, const char* note) {
    if (node_index >= 0) {
      RayTreeNode& node = context.tree->node(node_index);
      node.radiance = radiance;
      node.local = local;
      node.contribution = radiance * weight;
      if (note) node.note = note;
    }
    return radiance;
  };

  Intersection hit;
  if (!scene.intersect(ray, hit)) return finish(scene.background_along(ray.direction), {}, "left the scene");
  if (node_index >= 0) {
    RayTreeNode& node = context.tree->node(node_index);
    node.hit = true;
    node.object = scene.object_of(hit).name;
    node.t = hit.surface.t;
    node.position = hit.surface.position;
  }

  const Material& material = scene.material_of(hit);
  // 000 §4.2.1: the bump tilts the shading normal only; the geometry stays smooth.
  hit.surface.shading_normal = bumped_normal(material.bump, hit.surface);
  const Vec3 V = -ray.direction;
  // 000 §4.4: the see-through blend I = (1 − t)·I_surface + t·I_behind. The surface's own
  // share (1 − t) scales everything it sends out, so its secondary rays carry that weight.
  const double t = material.transparency.active()
                       ? material.transparency.at(std::fabs(dot(hit.surface.shading_normal, V)))
                       : 0.0;
  const double surface_share = 1 - t;
  const SurfaceProperties at = material.at(hit.surface);
  // A fully clear surface shows only what lies behind it.
  const Color local = surface_share > 0
                          ? local_illumination(scene, hit, at, V, limits.shadows, context, node_index)
                          : Color();
  Color radiance = local;

  const bool entering = dot(hit.surface.geometric_normal, V) > 0;
  const Vec3 N = face_forward(hit.surface.shading_normal, V);
  const Vec3 geometric = face_forward(hit.surface.geometric_normal, V);
  const double offset = scene.ray_offset(hit.surface.position);
  const Vec3 outside_origin = hit.surface.position + geometric * offset;
  const Vec3 inside_origin = hit.surface.position - geometric * offset;
  const double min_weight = limits.min_weight;
  const double surface_weight = weight * surface_share;
  std::string_view note_reached_depth, note_pruned;
  // A bumped normal can send a mirror direction below the true surface; it is folded back
  // above it (mirrored in the geometric tangent plane) rather than hitting the surface itself.
  const auto above = [&](Vec3 direction) {
    const double below = dot(direction, geometric);
    if (below < 0) direction -= geometric * (2 * below);
    return normalize(direction);
  };

  const bool wants_secondary = surface_share > 0 && (at.kr > 0 || at.kt > 0);
  if (wants_secondary && depth >= limits.max_depth) {
    note_reached_depth = "maximum depth reached";
  } else if (wants_secondary) {
    bool reflection_pruned = false, transmission_pruned = false;
    if (at.kr > 0) {
      if (surface_weight * at.kr >= min_weight) {
        ++context.counts.reflected;
        const Ray reflected{outside_origin, above(reflect(V, N))};
        radiance += at.kr * trace(scene, reflected, limits, RayKind::reflected, depth + 1,
                                  surface_weight * at.kr, context, node_index);
      } else {
        reflection_pruned = true;
      }
    }
    // A thin sheet (a window pane) passes its transmittance at the angle it is crossed
    // (shading/fresnel.h; kt its transmissivity), as in the path tracer and the shadow rays.
    const double kt =
        material.thin && at.kt > 0 ? thin_sheet(std::fabs(dot(N, V)), at.ior, at.kt).transmittance : at.kt;
    if (kt > 0) {
      if (surface_weight * kt >= min_weight) {
        // η1/η2: from outside (air) into the material, or back out.
        const double eta = entering ? 1.0 / at.ior : at.ior;
        Vec3 T;
        // A thin sheet (a window pane) does not bend the ray: it goes on as it came.
        if (material.thin ? (T = -V, true) : refract(V, N, eta, T)) {
          ++context.counts.refracted;
          // Folded below the surface when a bumped normal would turn it back out.
          Vec3 inward = normalize(T);
          const double outward = dot(inward, geometric);
          if (outward > 0) inward = normalize(inward - geometric * (2 * outward));
          const Ray refracted{inside_origin, inward};
          radiance += kt * trace(scene, refracted, limits, RayKind::refracted, depth + 1, surface_weight * kt,
                                 context, node_index);
        } else {
          // 000 §5.3: no transmitted ray; reflect with the flipped normal instead.
          ++context.counts.reflected;
          const Ray internal{outside_origin, above(reflect(V, N))};
          radiance += at.kt * trace(scene, internal, limits, RayKind::internal_reflection, depth + 1,
                                    surface_weight * at.kt, context, node_index);
        }
      } else {
        transmission_pruned = true;
      }
    }
    if (reflection_pruned && transmission_pruned)
      note_pruned = "reflection and transmission pruned: weight below whitted.min_weight";
    else if (reflection_pruned)
      note_pruned = "reflection pruned: weight below whitted.min_weight";
    else if (transmission_pruned)
      note_pruned = "transmission pruned: weight below whitted.min_weight";
  }

  if (t > 0) {
    // The ray goes on undeviated (the seed ignores the small displacement refraction causes).
    Color behind;
    if (depth >= limits.see_through_depth) {
      note_reached_depth = "maximum depth reached";
    } else if (weight * t >= min_weight) {
      ++context.counts.refracted;
      const Ray through{inside_origin, ray.direction};
      behind =
          trace(scene, through, limits, RayKind::see_through, depth + 1, weight * t, context, node_index);
    } else {
      note_pruned = "see-through pruned: weight below whitted.min_weight";
    }
    radiance = surface_share * radiance + t * behind;
  }
  const char* note = !note_reached_depth.empty() ? note_reached_depth.data()
                     : !note_pruned.empty()      ? note_pruned.data()
                                                 : nullptr;
  return finish(radiance, local, note);
}

}  // namespace

Color trace_ray_tree(const Scene& scene, const Ray& ray, const TreeLimits& limits, TraceContext& context) {
  return trace(scene, ray, limits, RayKind::primary, 0, 1.0, context, -1);
}

}  // namespace candela
