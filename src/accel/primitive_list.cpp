#include "accel/primitive_list.h"

namespace candela {

bool PrimitiveList::intersect(const Ray& ray, Intersection& intersection) const {
  // In index order, a hit at the same t as the best is never closer (closer_hit's tie rule),
  // so the strict t_max of each shape test keeps the lowest index.
  Ray nearest = ray;
  bool found = false;
  SurfaceHit hit;
  for (uint32_t index = 0; index < primitives_.size(); ++index) {
    if (primitives_[index].shape->intersect(nearest, hit)) {
      nearest.t_max = hit.t;  // 000 §5.6.2: farther hits are of no interest
      intersection.surface = hit;
      intersection.primitive = index;
      found = true;
    }
  }
  return found;
}

bool PrimitiveList::occluded(const Ray& ray) const {
  for (const Primitive& primitive : primitives_)
    if (primitive.shape->occluded(ray)) return true;
  return false;
}

}  // namespace candela
