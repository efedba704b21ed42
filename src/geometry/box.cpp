#include "geometry/box.h"

#include <cmath>
#include <stdexcept>
#include <utility>

#include "geometry/surface_sampling.h"
#include "geometry/tessellation.h"
#include "math/constants.h"

namespace candela {

Box::Box(const Vec3& lower, const Vec3& upper) : lower_(lower), upper_(upper) {
  if (!is_finite(lower) || !is_finite(upper)) throw std::invalid_argument("corners must be finite");
  if (!(lower.x < upper.x && lower.y < upper.y && lower.z < upper.z))
    throw std::invalid_argument("lower must be < upper on every axis");
}

double Box::nearest_t(const Ray& ray, int& face) const {
  // The slab test, remembering which slab sets the entry and the exit.
  double t_enter = -kInfinity, t_exit = kInfinity;
  int enter_face = 0, exit_face = 0;
  for (int axis = 0; axis < 3; ++axis) {
    const double origin = ray.origin[axis], direction = ray.direction[axis];
    if (direction == 0) {
      // Parallel to the slab: inside it (boundary included) or a miss.
      if (origin < lower_[axis] || origin > upper_[axis]) return kInfinity;
      continue;
    }
    const double inverse = 1.0 / direction;
    double t_lower = (lower_[axis] - origin) * inverse;
    double t_upper = (upper_[axis] - origin) * inverse;
    // Entering through the lower face when moving towards +axis.
    int near_face = axis, far_face = axis + 3;
    if (t_lower > t_upper) {
      std::swap(t_lower, t_upper);
      std::swap(near_face, far_face);
    }
    if (t_lower > t_enter) {
      t_enter = t_lower;
      enter_face = near_face;
    }
    if (t_upper < t_exit) {
      t_exit = t_upper;
      exit_face = far_face;
    }
  }
  if (t_enter > t_exit) return kInfinity;
  if (t_enter > ray.t_min && t_enter < ray.t_max) {
    face = enter_face;
    return t_enter;
  }
  if (t_exit > ray.t_min && t_exit < ray.t_max) {
    face = exit_face;
    return t_exit;
  }
  return kInfinity;
}

bool Box::intersect(const Ray& ray, SurfaceHit& hit) const {
  int face = 0;
  const double t = nearest_t(ray, face);
  if (t == kInfinity) return false;
  const int axis = face % 3;
  const bool upper_face = face >= 3;
  hit.t = t;
  hit.position = ray.at(t);
  hit.position[axis] = upper_face ? upper_[axis] : lower_[axis];  // exactly on the face
  Vec3 normal;
  normal[axis] = upper_face ? 1.0 : -1.0;
  hit.geometric_normal = normal;
  hit.shading_normal = normal;
  hit.object_position = hit.position;
  int u_axis = (axis + 1) % 3, v_axis = (axis + 2) % 3;
  if (!upper_face) std::swap(u_axis, v_axis);
  const Vec3 extent = upper_ - lower_;
  hit.uv = {std::clamp((hit.position[u_axis] - lower_[u_axis]) / extent[u_axis], 0.0, 1.0),
            std::clamp((hit.position[v_axis] - lower_[v_axis]) / extent[v_axis], 0.0, 1.0)};
  hit.dpdu = Vec3{};
  hit.dpdu[u_axis] = extent[u_axis];
  hit.dpdv = Vec3{};
  hit.dpdv[v_axis] = extent[v_axis];
  return true;
}

bool Box::occluded(const Ray& ray) const {
  int face = 0;
  return nearest_t(ray, face) < kInfinity;
}

Bounds3 Box::bounds() const {
  return {lower_, upper_};
}

double Box::area() const {
  const Vec3 e = upper_ - lower_;
  return 2 * (e.x * e.y + e.y * e.z + e.z * e.x);
}

bool Box::sample_area(const Vec2& u, SurfaceSample& sample) const {
  const Vec3 e = upper_ - lower_;
  // Faces numbered as in nearest_t: axis k lower is k, upper is k + 3.
  const double face_areas[6] = {e.y * e.z, e.z * e.x, e.x * e.y, e.y * e.z, e.z * e.x, e.x * e.y};
  double choice = u.x;
  const int face = pick_by_area(face_areas, choice);
  if (face == 6) return false;
  const int axis = face % 3;
  const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
  Vec3 p;
  p[axis] = face >= 3 ? upper_[axis] : lower_[axis];
  p[a1] = lower_[a1] + e[a1] * choice;
  p[a2] = lower_[a2] + e[a2] * u.y;
  sample.position = p;
  sample.normal = Vec3{};
  sample.normal[axis] = face >= 3 ? 1.0 : -1.0;
  sample.pdf = 1 / area();
  return true;
}

double Box::pdf_area(const SurfaceHit&) const {
  return 1 / area();
}

void Box::tessellate(const TessellationSettings&, TriangleMesh& mesh) const {
  MeshAppender out(mesh);
  // Corner i takes the upper bound on axis k when bit k of i is set.
  std::array<uint32_t, 8> corners;
  for (int i = 0; i < 8; ++i) {
    Vec3 p;
    for (int axis = 0; axis < 3; ++axis) p[axis] = ((i >> axis) & 1) ? upper_[axis] : lower_[axis];
    corners[i] = out.vertex(p);
  }
  for (int face = 0; face < 6; ++face) {
    // As intersect: axis k, u along k+1 and v along k+2 on the upper face, swapped on the lower
    // face, so that dpdu × dpdv is outward and (u, v) counter-clockwise is too.
    const int axis = face % 3;
    const bool upper_face = face >= 3;
    int u_axis = (axis + 1) % 3, v_axis = (axis + 2) % 3;
    if (!upper_face) std::swap(u_axis, v_axis);
    const auto corner = [&](int u, int v) {
      return corners[(upper_face ? 1 << axis : 0) | (u << u_axis) | (v << v_axis)];
    };
    out.triangle({corner(0, 0), corner(1, 0), corner(1, 1)}, {Vec2{0, 0}, Vec2{1, 0}, Vec2{1, 1}});
    out.triangle({corner(0, 0), corner(1, 1), corner(0, 1)}, {Vec2{0, 0}, Vec2{1, 1}, Vec2{0, 1}});
  }
}

}  // namespace candela
