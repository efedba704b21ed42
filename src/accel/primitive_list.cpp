#include "accel/primitive_list.h"

namespace candela {

void PrimitiveList::build(std::span<const Primitive> primitives) {
  primitives_ = primitives;
  groups_.clear();
  if (bounding_volume_ == BoundingVolumeKind::none) return;
  for (uint32_t first = 0; first < primitives.size();) {
    uint32_t end = first + 1;
    while (end < primitives.size() && primitives[end].object == primitives[first].object) ++end;
    groups_.push_back(
        {first, end - first, ObjectBound(bounding_volume_, primitives.subspan(first, end - first))});
    first = end;
  }
}

bool PrimitiveList::intersect(const Ray& ray, Intersection& intersection) const {
  // In index order, a hit at the same t as the best is never closer (closer_hit's tie rule),
  // so the strict t_max of each shape test keeps the lowest index.
  Ray nearest = ray;
  bool found = false;
  SurfaceHit hit;
  const auto test = [&](uint32_t first, uint32_t end) {
    for (uint32_t index = first; index < end; ++index) {
      if (primitives_[index].shape->intersect(nearest, hit)) {
        nearest.t_max = hit.t;  // 000 §5.6.2: farther hits are of no interest
        intersection.surface = hit;
        intersection.primitive = index;
        found = true;
      }
    }
  };
  if (groups_.empty()) {
    test(0, static_cast<uint32_t>(primitives_.size()));
  } else {
    for (const Group& group : groups_)
      if (group.bound.hit_by(nearest)) test(group.first, group.first + group.count);
  }
  return found;
}

bool PrimitiveList::occluded(const Ray& ray) const {
  if (groups_.empty()) {
    for (const Primitive& primitive : primitives_)
      if (primitive.shape->occluded(ray)) return true;
    return false;
  }
  for (const Group& group : groups_) {
    if (!group.bound.hit_by(ray)) continue;
    for (uint32_t index = group.first; index < group.first + group.count; ++index)
      if (primitives_[index].shape->occluded(ray)) return true;
  }
  return false;
}

AcceleratorReport PrimitiveList::report() const {
  AcceleratorReport report;
  report.figures = {{"primitives", static_cast<double>(primitives_.size())},
                    {"bounding volumes", static_cast<double>(groups_.size())}};
  report.bytes = groups_.size() * sizeof(Group);
  return report;
}

}  // namespace candela
