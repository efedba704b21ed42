// The ray tree of one pixel (000 §5.5, Figure 36): every ray, what it hit, its weight and
// its contribution. Printed by `candela render --pixel X,Y`.
#pragma once

#include <string>
#include <vector>

#include "math/vector.h"

namespace candela {

enum class RayKind { primary, reflected, refracted, internal_reflection, see_through, shadow };
const char* ray_kind_name(RayKind kind);

struct RayTreeNode {
  int parent = -1;
  RayKind kind = RayKind::primary;
  int depth = 0;
  Vec3 origin, direction;
  bool hit = false;
  std::string object;  // name of what it hit
  double t = 0;
  Vec3 position;
  double weight = 1;    // product of the k's from the eye (000 §5.5)
  Color transmittance;  // shadow rays: the s of 001, per channel
  Color local;          // the local model's part at the hit
  Color radiance;       // what the ray brings back
  Color contribution;   // radiance × weight × k of the last bounce: its share of the pixel
  std::string note;     // why the branch ended, what it saw
};

class RayTree {
 public:
  int add(const RayTreeNode& node) {
    nodes_.push_back(node);
    return static_cast<int>(nodes_.size() - 1);
  }
  RayTreeNode& node(int index) { return nodes_[index]; }
  const std::vector<RayTreeNode>& nodes() const { return nodes_; }
  std::string to_text() const;

 private:
  std::vector<RayTreeNode> nodes_;
};

}  // namespace candela
