#include "radiosity/radiosity_hierarchy.h"

#include <algorithm>
#include <utility>

#include "scene/scene.h"

namespace candela {
namespace {

HierarchySurface make_hierarchy_surface(const Scene& scene, const CornerTriangle& triangle,
                                        uint32_t primitive, uint32_t input) {
  HierarchySurface made;
  made.surface = make_radiosity_surface(scene, triangle, primitive);
  for (int k = 0; k < 3; ++k) {
    made.object_corners[k] = triangle[k].object_position;
    made.uvs[k] = triangle[k].uv;
  }
  made.input = input;
  return made;
}

HierarchyNode surface_node(const RadiositySurface& surface, uint32_t payload) {
  HierarchyNode node;
  node.payload = payload;
  node.centre = surface.centroid;
  for (const Vec3& corner : surface.corners)
    node.radius = std::max(node.radius, length(corner - surface.centroid));
  node.area = surface.area;
  node.reflectance_max = std::max({surface.reflectance.r, surface.reflectance.g, surface.reflectance.b});
  return node;
}

}  // namespace

RadiosityHierarchy::RadiosityHierarchy(const Scene& scene, const RadiosityInput& input)
    : scene_size(input.scene_size) {
  const std::size_t count = input.triangles.size();
  surfaces.reserve(count);
  for (std::size_t t = 0; t < count; ++t)
    surfaces.push_back(
        make_hierarchy_surface(scene, input.triangles[t], input.primitives[t], static_cast<uint32_t>(t)));
  input_order.resize(count);
  for (std::size_t t = 0; t < count; ++t) input_order[t] = static_cast<uint32_t>(t);
  root_of_input.assign(count, kNoNode);
  if (count == 0) return;
  // Top-down: a range of input_order becomes a cluster (two or more triangles) or a root (one).
  struct Pending {
    uint32_t node, begin, end;
  };
  const auto place = [&](uint32_t node, uint32_t begin, uint32_t end) {
    if (end - begin == 1) {
      const uint32_t t = input_order[begin];
      nodes[node] = surface_node(surfaces[t].surface, t);
      root_of_input[t] = node;
      return false;
    }
    HierarchyCluster cluster{{}, begin, end - begin};
    for (uint32_t k = begin; k < end; ++k)
      for (const Vec3& corner : surfaces[input_order[k]].surface.corners) cluster.box.extend(corner);
    HierarchyNode& made = nodes[node];
    made.is_cluster = true;
    made.payload = static_cast<uint32_t>(clusters.size());
    made.centre = (cluster.box.lower + cluster.box.upper) * 0.5;
    made.radius = 0.5 * length(cluster.box.diagonal());
    clusters.push_back(cluster);
    return true;
  };
  nodes.resize(1);
  std::vector<Pending> pending;
  if (place(0, 0, static_cast<uint32_t>(count))) pending.push_back({0, 0, static_cast<uint32_t>(count)});
  while (!pending.empty()) {
    const Pending job = pending.back();
    pending.pop_back();
    Bounds3 centroids;
    for (uint32_t k = job.begin; k < job.end; ++k)
      centroids.extend(surfaces[input_order[k]].surface.centroid);
    const Vec3 extent = centroids.diagonal();
    const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
    const uint32_t middle = job.begin + (job.end - job.begin) / 2;
    // Ties broken by the triangle's index: the same tree on every machine.
    std::nth_element(input_order.begin() + job.begin, input_order.begin() + middle,
                     input_order.begin() + job.end, [&](uint32_t a, uint32_t b) {
                       const double ca = surfaces[a].surface.centroid[axis],
                                    cb = surfaces[b].surface.centroid[axis];
                       return ca < cb || (ca == cb && a < b);
                     });
    const auto first = static_cast<uint32_t>(nodes.size());
    nodes.resize(nodes.size() + 2);
    nodes[job.node].first_child = first;
    nodes[job.node].child_count = 2;
    const std::array<std::pair<uint32_t, uint32_t>, 2> halves{{{job.begin, middle}, {middle, job.end}}};
    for (uint32_t c = 0; c < 2; ++c) {
      const bool cluster = place(first + c, halves[c].first, halves[c].second);
      nodes[first + c].parent = job.node;  // after place, which makes the node anew
      if (cluster) pending.push_back({first + c, halves[c].first, halves[c].second});
    }
  }
  // A cluster's area and reflectance bound: its children's (children come after parents).
  for (std::size_t i = nodes.size(); i-- > 0;) {
    HierarchyNode& node = nodes[i];
    if (!node.is_cluster) continue;
    node.area = 0;
    node.reflectance_max = 0;
    for (uint32_t c = node.first_child; c < node.first_child + node.child_count; ++c) {
      node.area += nodes[c].area;
      node.reflectance_max = std::max(node.reflectance_max, nodes[c].reflectance_max);
    }
  }
}

std::array<Vec3, 4> RadiosityHierarchy::child_centroids(uint32_t node) const {
  const auto& [a, b, c] = surface(node).corners;
  return {(a * 4 + b + c) / 6, (a + b * 4 + c) / 6, (a + b + c * 4) / 6, (a + b + c) / 3};
}

uint32_t RadiosityHierarchy::split(const Scene& scene, uint32_t node) {
  if (nodes[node].child_count > 0) return nodes[node].first_child;
  const HierarchySurface parent = surfaces[nodes[node].payload];
  CornerTriangle corners;
  for (int k = 0; k < 3; ++k)
    corners[k] = {parent.surface.corners[k], parent.object_corners[k], parent.uvs[k]};
  const MeshCorner ab = midpoint(corners[0], corners[1]), bc = midpoint(corners[1], corners[2]),
                   ca = midpoint(corners[2], corners[0]);
  // The corner triangles in the order of child_centroids, then the middle one (all wound as the parent).
  const std::array<CornerTriangle, 4> pieces{
      {{corners[0], ab, ca}, {ab, corners[1], bc}, {ca, bc, corners[2]}, {ab, bc, ca}}};
  const auto first = static_cast<uint32_t>(nodes.size());
  for (const CornerTriangle& piece : pieces) {
    const auto payload = static_cast<uint32_t>(surfaces.size());
    surfaces.push_back(make_hierarchy_surface(scene, piece, parent.surface.primitive, parent.input));
    HierarchyNode child = surface_node(surfaces.back().surface, payload);
    child.parent = node;
    child.depth = static_cast<uint16_t>(nodes[node].depth + 1);
    nodes.push_back(child);
  }
  nodes[node].first_child = first;
  nodes[node].child_count = 4;
  return first;
}

std::size_t RadiosityHierarchy::memory_bytes() const {
  return nodes.capacity() * sizeof(HierarchyNode) + surfaces.capacity() * sizeof(HierarchySurface) +
         clusters.capacity() * sizeof(HierarchyCluster) +
         (input_order.capacity() + root_of_input.capacity()) * 4;
}

}  // namespace candela
