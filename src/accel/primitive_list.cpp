#include "accel/primitive_list.h"

namespace candela {

void PrimitiveList::build(std::span<const Primitive> primitives) {
  primitives_ = primitives;
  tested_ = reportable_primitives(primitives);
  groups_.clear();
  if (bounding_volume_ == BoundingVolumeKind::none) return;
  const auto count = static_cast<uint32_t>(tested_.size());
  for (uint32_t first = 0; first < count;) {
    const uint32_t object = primitives[tested_[first]].object;
    uint32_t end = first + 1;
    while (end < count && primitives[tested_[end]].object == object) ++end;
    // Over the primitives from the run's first to its last: those left out between them only
    // make the volume larger.
    const uint32_t lowest = tested_[first], highest = tested_[end - 1];
    groups_.push_back({first, end - first,
                       ObjectBound(bounding_volume_, primitives.subspan(lowest, highest - lowest + 1))});
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
    for (uint32_t position = first; position < end; ++position) {
      const uint32_t index = tested_[position];
      if (primitives_[index].shape->intersect(nearest, hit)) {
        nearest.t_max = hit.t;  // 000 §5.6.2: farther hits are of no interest
        intersection.surface = hit;
        intersection.primitive = index;
        found = true;
      }
    }
  };
  if (groups_.empty()) {
    test(0, static_cast<uint32_t>(tested_.size()));
  } else {
    for (const Group& group : groups_)
      if (group.bound.hit_by(nearest)) test(group.first, group.first + group.count);
  }
  return found;
}

bool PrimitiveList::occluded(const Ray& ray) const {
  if (groups_.empty()) {
    for (const uint32_t index : tested_)
      if (primitives_[index].shape->occluded(ray)) return true;
    return false;
  }
  for (const Group& group : groups_) {
    if (!group.bound.hit_by(ray)) continue;
    for (uint32_t position = group.first; position < group.first + group.count; ++position)
      if (primitives_[tested_[position]].shape->occluded(ray)) return true;
  }
  return false;
}

AcceleratorReport PrimitiveList::report() const {
  AcceleratorReport report;
  report.figures = {{"primitives", static_cast<double>(tested_.size())},
                    {"bounding volumes", static_cast<double>(groups_.size())}};
  report.bytes = groups_.size() * sizeof(Group) + tested_.size() * sizeof(uint32_t);
  return report;
}

}  // namespace candela
