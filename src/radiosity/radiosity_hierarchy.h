// The nodes hierarchical radiosity links (SPEC §10.1; Hanrahan, Salzman and Aupperle 1991;
// Smits, Arvo and Greenberg 1994; Sillion 1995): every input triangle of the scene (tessellated,
// radiosity_input) is the root of a quadtree — a triangle splits into four by its edge midpoints —
// and a volume hierarchy of clusters stands over the input triangles, so that light can be
// exchanged between groups of surfaces without a link per pair of input triangles.
//
// Nodes live in one array; a node's children are consecutive and come after it (a parent's index is
// always below its children's), so one pass in index order visits parents first (push) and one in
// reverse visits children first (pull).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "math/bounds.h"
#include "math/vector.h"
#include "radiosity/radiosity_mesh.h"

namespace candela {

class Scene;

inline constexpr uint32_t kNoNode = UINT32_MAX;

struct HierarchyNode {
  uint32_t parent = kNoNode;
  uint32_t first_child = kNoNode;  // children are first_child … first_child + child_count − 1
  uint8_t child_count = 0;
  bool is_cluster = false;
  uint16_t depth = 0;          // quadtree level (0: an input triangle); 0 for clusters
  uint32_t payload = 0;        // index into surfaces (a surface) or clusters (a cluster)
  Vec3 centre;                 // surface: centroid; cluster: its box's centre
  double radius = 0;           // of a sphere about centre holding the node
  double area = 0;             // surface: its area; cluster: the area of the input triangles inside
  double reflectance_max = 0;  // the largest channel of ρ (of any surface inside, for a cluster)
};

struct HierarchySurface {
  RadiositySurface surface;  // ρ, E at its centroid; first_shot = ρ × the mean of direct_samples
  std::array<Vec3, 3> object_corners;
  std::array<Vec2, 3> uvs;
  uint32_t input = 0;  // the input triangle it is (part of)
  // The power by which its first shot is uncertain: A × the largest channel of ρ × the spread of
  // the direct irradiance at the centroids of its four children.
  double direct_error = 0;
  bool direct_done = false;  // direct_error and first_shot computed
};

struct HierarchyCluster {
  Bounds3 box;
  uint32_t first_input = 0, input_count = 0;  // a range of RadiosityHierarchy::input_order
};

class RadiosityHierarchy {
 public:
  // Roots for every input triangle and clusters over them, split at the median of the longest axis
  // of the centroids' box until one triangle is left (a binary tree: n − 1 clusters over n
  // triangles); the clusters' root is node 0 (with one input triangle, node 0 is that triangle).
  // The direct light is not computed here.
  RadiosityHierarchy(const Scene& scene, const RadiosityInput& input);

  std::vector<HierarchyNode> nodes;
  std::vector<HierarchySurface> surfaces;
  std::vector<HierarchyCluster> clusters;
  std::vector<uint32_t> input_order;    // input triangles in cluster order
  std::vector<uint32_t> root_of_input;  // the node of each input triangle
  double scene_size = 0;

  uint32_t root() const { return 0; }
  bool is_leaf(uint32_t node) const { return nodes[node].child_count == 0; }
  const RadiositySurface& surface(uint32_t node) const { return surfaces[nodes[node].payload].surface; }
  // The longest edge of a surface node.
  double edge(uint32_t node) const { return longest_edge(surface(node)); }

  // Splits surface node `node` into the four triangles of its edge midpoints (ρ and E evaluated at
  // their centroids; the direct light left to compute). Returns the first child; a node already
  // split keeps its children.
  uint32_t split(const Scene& scene, uint32_t node);

  // The centroids of the four triangles of a surface node's midpoint split.
  std::array<Vec3, 4> child_centroids(uint32_t node) const;

  std::size_t memory_bytes() const;
};

}  // namespace candela
