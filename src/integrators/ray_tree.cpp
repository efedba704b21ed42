#include "integrators/ray_tree.h"

#include <fmt/format.h>

#include <functional>

namespace candela {

const char* ray_kind_name(RayKind kind) {
  switch (kind) {
    case RayKind::primary:
      return "primary";
    case RayKind::reflected:
      return "reflected";
    case RayKind::refracted:
      return "refracted";
    case RayKind::internal_reflection:
      return "internal reflection";
    case RayKind::see_through:
      return "see-through";
    case RayKind::shadow:
      return "shadow";
  }
  return "?";
}

namespace {
std::string format_vec(const Vec3& v) {
  return fmt::format("({:.4g}, {:.4g}, {:.4g})", v.x, v.y, v.z);
}
std::string format_color(const Color& c) {
  return fmt::format("[{:.4g}, {:.4g}, {:.4g}]", c.r, c.g, c.b);
}
}  // namespace

std::string RayTree::to_text() const {
  std::string text;
  std::function<void(int, const std::string&)> print = [&](int index, const std::string& indent) {
    const RayTreeNode& n = nodes_[index];
    text += indent + fmt::format("{} ray, depth {}, weight {:.4g}: from {} dir {}\n", ray_kind_name(n.kind),
                                 n.depth, n.weight, format_vec(n.origin), format_vec(n.direction));
    const std::string detail = indent + "    ";
    if (n.kind == RayKind::shadow) {
      text += detail + fmt::format("transmittance s = {}", format_color(n.transmittance));
    } else if (n.hit) {
      text += detail + fmt::format("hit {} at t = {:.6g}, point {}; local {}, radiance {}, contribution {}",
                                   n.object, n.t, format_vec(n.position), format_color(n.local),
                                   format_color(n.radiance), format_color(n.contribution));
    } else {
      text += detail + fmt::format("miss: background {}, contribution {}", format_color(n.radiance),
                                   format_color(n.contribution));
    }
    if (!n.note.empty()) text += " (" + n.note + ")";
    text += "\n";
    for (int child = index + 1; child < static_cast<int>(nodes_.size()); ++child)
      if (nodes_[child].parent == index) print(child, indent + "  ");
  };
  for (int index = 0; index < static_cast<int>(nodes_.size()); ++index)
    if (nodes_[index].parent < 0) print(index, "");
  return text;
}

}  // namespace candela
