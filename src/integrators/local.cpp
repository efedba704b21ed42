#include "integrators/local.h"

#include "integrators/direct_lighting.h"

namespace candela {

Color LocalMethod::trace_primary(const Scene& scene, const Ray& ray, TraceContext& context) const {
  int node_index = -1;
  if (context.tree) {
    RayTreeNode node;
    node.origin = ray.origin;
    node.direction = ray.direction;
    node_index = context.tree->add(node);
  }
  Intersection hit;
  Color radiance = scene.background;
  Color local;
  if (scene.intersect(ray, hit)) {
    local = local_illumination(scene, hit, -ray.direction, scene.local.shadows, context, node_index);
    radiance = local;
    if (node_index >= 0) {
      RayTreeNode& node = context.tree->node(node_index);
      node.hit = true;
      node.object = scene.object_of(hit).name;
      node.t = hit.surface.t;
      node.position = hit.surface.position;
    }
  }
  if (node_index >= 0) {
    RayTreeNode& node = context.tree->node(node_index);
    node.local = local;
    node.radiance = node.contribution = radiance;
    if (!node.hit) node.note = "left the scene";
  }
  return radiance;
}

}  // namespace candela
