#include "accel/octree.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <utility>

#include "accel/subdivision.h"

namespace candela {

namespace {
// Nodes holding at least this many primitives build their children in parallel.
constexpr std::size_t kParallelCount = 1024;
}  // namespace

bool Octree::worth_cutting(const std::array<std::vector<uint32_t>, 8>& children, std::size_t count) {
  std::size_t references = 0, non_empty = 0, full = 0;
  for (const auto& child : children) {
    references += child.size();
    if (!child.empty()) ++non_empty;
    if (child.size() == count) ++full;
  }
  return references <= std::size_t{kMaxDuplication} * count && !(non_empty >= 2 && full == non_empty);
}

struct Octree::BuildNode {
  uint32_t count = 0;
  std::vector<uint32_t> primitives;  // a leaf's
  std::vector<BuildNode> children;   // 8 for an internal node, none for a leaf
};

Octree::Octree(int max_primitives, int max_depth) : max_primitives_(max_primitives), max_depth_(max_depth) {
  if (max_primitives < 0) throw std::invalid_argument("octree max_primitives must not be negative");
  if (max_depth < 0 || max_depth > kMaxDepth)
    throw std::invalid_argument("octree max_depth must lie in [0, 32]");
}

void Octree::build(std::span<const Primitive> primitives) {
  primitives_ = primitives;
  nodes_.clear();
  indices_.clear();
  subdivision::PrimitiveSplit split = subdivision::split_primitives(primitives);
  unbounded_ = std::move(split.unbounded);
  if (split.bounded.empty()) {
    root_ = Bounds3{};
    root_size_ = 0;
    return;
  }
  // The root cube: anchored at the scene's lower corner (grown by the margin), so that a flat
  // scene does not lie on the mid-planes of the first cuts.
  margin_ = split.margin;
  const Vec3 extent = split.scene.diagonal();
  root_size_ = std::max({extent.x, extent.y, extent.z}) + 2 * margin_;
  root_.lower = split.scene.lower - Vec3{margin_, margin_, margin_};
  for (int depth = 0; depth < static_cast<int>(cell_size_.size()); ++depth)
    cell_size_[depth] = std::ldexp(root_size_, -depth);
  for (int axis = 0; axis < 3; ++axis) root_.upper[axis] = face(axis, 1, 0);
  bounds_ = std::move(split.bounds);

  BuildNode root;
  subdivide(root, std::move(split.bounded), 0, {0, 0, 0});
  nodes_.emplace_back();
  flatten(root, 0);
  bounds_ = {};
}

void Octree::subdivide(BuildNode& node, std::vector<uint32_t> primitives, int depth,
                       std::array<uint32_t, 3> coordinates) const {
  node.count = static_cast<uint32_t>(primitives.size());
  if (primitives.size() <= static_cast<std::size_t>(max_primitives_) || depth >= max_depth_) {
    node.primitives = std::move(primitives);
    return;
  }
  std::array<double, 3> mid{};
  for (int axis = 0; axis < 3; ++axis) mid[axis] = face(axis, 2 * uint64_t{coordinates[axis]} + 1, depth + 1);
  // Child c is the upper half along axis a when bit a of c is set.
  std::array<std::vector<uint32_t>, 8> lists;
  for (uint32_t index : primitives) {
    const Bounds3& bounds = bounds_[index];
    std::array<std::array<bool, 2>, 3> side{};
    for (int axis = 0; axis < 3; ++axis) {
      side[axis][0] = bounds.lower[axis] - margin_ <= mid[axis];
      side[axis][1] = bounds.upper[axis] + margin_ >= mid[axis];
    }
    for (int child = 0; child < 8; ++child)
      if (side[0][child & 1] && side[1][(child >> 1) & 1] && side[2][(child >> 2) & 1])
        lists[child].push_back(index);
  }
  if (!worth_cutting(lists, primitives.size())) {
    node.primitives = std::move(primitives);
    return;
  }
  primitives = {};
  node.children.resize(8);
  const auto build_child = [&](int child) {
    std::array<uint32_t, 3> child_coordinates{};
    for (int axis = 0; axis < 3; ++axis)
      child_coordinates[axis] = 2 * coordinates[axis] + static_cast<uint32_t>((child >> axis) & 1);
    subdivide(node.children[child], std::move(lists[child]), depth + 1, child_coordinates);
  };
  if (node.count >= kParallelCount) {
    tbb::parallel_for(0, 8, build_child);
  } else {
    for (int child = 0; child < 8; ++child) build_child(child);
  }
}

void Octree::flatten(BuildNode& node, uint32_t slot) {
  const uint16_t depth = nodes_[slot].depth;
  if (node.children.empty()) {
    if (indices_.size() + node.primitives.size() > std::numeric_limits<uint32_t>::max())
      throw std::length_error("octree: more than 2^32 primitive references");
    nodes_[slot] = {static_cast<uint32_t>(indices_.size()), node.count, depth, 1};
    indices_.insert(indices_.end(), node.primitives.begin(), node.primitives.end());
    node.primitives = {};
    return;
  }
  const auto first = static_cast<uint32_t>(nodes_.size());
  nodes_[slot] = {first, node.count, depth, 0};
  nodes_.resize(nodes_.size() + 8, Node{0, 0, static_cast<uint16_t>(depth + 1), 1});
  for (uint32_t child = 0; child < 8; ++child) flatten(node.children[child], first + child);
  node.children = {};
}

const Octree::Node& Octree::leaf_at(const Vec3& point, Bounds3* box) const {
  const Node* node = &nodes_.at(0);
  std::array<uint32_t, 3> coordinates{0, 0, 0};
  while (!node->leaf) {
    int child = 0;
    for (int axis = 0; axis < 3; ++axis) {
      const int upper =
          point[axis] >= face(axis, 2 * uint64_t{coordinates[axis]} + 1, node->depth + 1) ? 1 : 0;
      child |= upper << axis;
      coordinates[axis] = 2 * coordinates[axis] + static_cast<uint32_t>(upper);
    }
    node = &nodes_[node->first + static_cast<uint32_t>(child)];
  }
  if (box) {
    for (int axis = 0; axis < 3; ++axis) {
      box->lower[axis] = face(axis, coordinates[axis], node->depth);
      box->upper[axis] = face(axis, uint64_t{coordinates[axis]} + 1, node->depth);
    }
  }
  return *node;
}

template <typename Visit>
void Octree::walk(const Ray& ray, double t_max, Visit&& visit) const {
  if (nodes_.empty()) return;
  Ray clipped = ray;
  clipped.t_max = t_max;
  double t_enter = 0, t_exit = 0;
  if (!root_.intersect(clipped, t_enter, t_exit)) return;

  struct Entry {
    uint32_t node;
    std::array<uint32_t, 3> coordinates;
    double t_enter, t_exit;
  };
  // Each internal node popped pushes at most 4 children: at most 3 pending per level.
  std::array<Entry, 3 * kMaxDepth + 2> stack;
  int top = 0;
  stack[top++] = {0, {0, 0, 0}, t_enter, t_exit};
  while (top > 0) {
    const Entry entry = stack[--top];
    const Node& node = nodes_[entry.node];
    if (node.leaf) {
      if (node.count > 0 && visit(leaf_primitives(node), entry.t_enter, entry.t_exit)) return;
      continue;
    }
    // The child holding the entry point, and where the ray crosses the mid-planes inside the
    // node. Everything follows from the parametric t, so the children's intervals tile the
    // node's interval exactly.
    int child = 0;
    std::array<std::pair<double, int>, 3> crossings{};
    int crossing_count = 0;
    for (int axis = 0; axis < 3; ++axis) {
      const double mid = face(axis, 2 * uint64_t{entry.coordinates[axis]} + 1, node.depth + 1);
      const double direction = ray.direction[axis];
      if (direction == 0) {
        if (ray.origin[axis] >= mid) child |= 1 << axis;
        continue;
      }
      const double t = (mid - ray.origin[axis]) / direction;
      const bool passed = entry.t_enter >= t;
      if (passed == (direction > 0)) child |= 1 << axis;
      if (!passed && t < entry.t_exit) crossings[crossing_count++] = {t, axis};
    }
    for (int k = 1; k < crossing_count; ++k)  // insertion sort of at most 3
      for (int j = k; j > 0 && crossings[j].first < crossings[j - 1].first; --j)
        std::swap(crossings[j], crossings[j - 1]);
    std::array<Entry, 4> children{};
    int child_count = 0;
    double from = entry.t_enter;
    for (int k = 0; k <= crossing_count; ++k) {
      const double to = k < crossing_count ? crossings[k].first : entry.t_exit;
      Entry& next = children[child_count++];
      next.node = node.first + static_cast<uint32_t>(child);
      for (int axis = 0; axis < 3; ++axis)
        next.coordinates[axis] = 2 * entry.coordinates[axis] + static_cast<uint32_t>((child >> axis) & 1);
      next.t_enter = from;
      next.t_exit = to;
      if (k < crossing_count) child ^= 1 << crossings[k].second;
      from = to;
    }
    for (int k = child_count - 1; k >= 0; --k) {
      const Node& next = nodes_[children[k].node];
      if (next.leaf && next.count == 0) continue;
      stack[top++] = children[k];
    }
  }
}

bool Octree::intersect(const Ray& ray, Intersection& intersection) const {
  subdivision::NearestHit nearest(primitives_, ray, intersection);
  for (uint32_t index : unbounded_) nearest.test(index);
  subdivision::RayMailbox mailbox;
  walk(ray, nearest.search_limit(), [&](std::span<const uint32_t> leaf, double leaf_enter, double leaf_exit) {
    // Leaves come front to back: one that starts beyond the best hit holds nothing nearer.
    if (nearest.found() && nearest.best_t() < leaf_enter) return true;
    for (uint32_t index : leaf)
      if (mailbox.insert(index)) nearest.test(index);
    // 000 §5.7.2: the best hit is final once the walk has passed it.
    return nearest.found() && nearest.best_t() <= leaf_exit;
  });
  return nearest.found();
}

bool Octree::occluded(const Ray& ray) const {
  for (uint32_t index : unbounded_)
    if (primitives_[index].shape->occluded(ray)) return true;
  bool hit = false;
  subdivision::RayMailbox mailbox;
  walk(ray, ray.t_max, [&](std::span<const uint32_t> leaf, double, double) {
    for (uint32_t index : leaf)
      if (mailbox.insert(index) && primitives_[index].shape->occluded(ray)) return hit = true;
    return false;
  });
  return hit;
}

AcceleratorReport Octree::report() const {
  std::size_t leaves = 0, non_empty = 0, depth = 0;
  for (const Node& node : nodes_) {
    depth = std::max<std::size_t>(depth, node.depth);
    if (!node.leaf) continue;
    ++leaves;
    if (node.count > 0) ++non_empty;
  }
  AcceleratorReport report;
  report.figures = {
      {"nodes", static_cast<double>(nodes_.size())},
      {"leaves", static_cast<double>(leaves)},
      {"non-empty leaves", static_cast<double>(non_empty)},
      {"max depth", static_cast<double>(depth)},
      {"primitives per non-empty leaf",
       non_empty == 0 ? 0.0 : static_cast<double>(indices_.size()) / static_cast<double>(non_empty)},
      {"references", static_cast<double>(indices_.size())},
      {"unbounded", static_cast<double>(unbounded_.size())},
  };
  report.bytes =
      nodes_.capacity() * sizeof(Node) + (indices_.capacity() + unbounded_.capacity()) * sizeof(uint32_t);
  return report;
}

}  // namespace candela
