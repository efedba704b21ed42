// Axis-aligned bounding box with the slab test (001: "volume incadrator paralelipipedic").
#pragma once

#include "math/constants.h"
#include "math/ray.h"
#include "math/vector.h"

namespace candela {

struct Bounds3 {
  Vec3 lower{kInfinity, kInfinity, kInfinity};
  Vec3 upper{-kInfinity, -kInfinity, -kInfinity};

  static Bounds3 of_point(const Vec3& p) { return {p, p}; }
  bool empty() const { return lower.x > upper.x || lower.y > upper.y || lower.z > upper.z; }
  void extend(const Vec3& p) {
    lower = min(lower, p);
    upper = max(upper, p);
  }
  void extend(const Bounds3& b) {
    lower = min(lower, b.lower);
    upper = max(upper, b.upper);
  }
  Vec3 diagonal() const { return upper - lower; }
  Vec3 center() const { return (lower + upper) * 0.5; }
  bool contains(const Vec3& p) const {
    return p.x >= lower.x && p.x <= upper.x && p.y >= lower.y && p.y <= upper.y && p.z >= lower.z &&
           p.z <= upper.z;
  }
  bool is_finite() const { return candela::is_finite(lower) && candela::is_finite(upper); }

  // Slab test: the parametric interval where the ray is inside the box, clipped to
  // [t_min, t_max]; false when it is empty.
  bool intersect(const Ray& ray, double& t_enter, double& t_exit) const {
    double t0 = ray.t_min, t1 = ray.t_max;
    for (int axis = 0; axis < 3; ++axis) {
      const double inverse = 1.0 / ray.direction[axis];
      double t_near = (lower[axis] - ray.origin[axis]) * inverse;
      double t_far = (upper[axis] - ray.origin[axis]) * inverse;
      if (t_near > t_far) std::swap(t_near, t_far);
      // NaN (0 * inf when the origin lies on a slab of a parallel ray) keeps the old bound.
      if (t_near > t0) t0 = t_near;
      if (t_far < t1) t1 = t_far;
      if (t0 > t1) return false;
    }
    t_enter = t0;
    t_exit = t1;
    return true;
  }
};

}  // namespace candela
