// The frame shared by the shapes of revolution from a base point to a cap point (cylinder,
// cone): the base at the origin and the axis along +z, reached by a rotation and a
// translation, so ray distances are the same in both frames.
#pragma once

#include <cmath>

#include "geometry/surface_hit.h"
#include "math/ray.h"

namespace candela {

struct SurfaceSample;

class AxialFrame {
 public:
  // Throws std::invalid_argument when the points are not finite or coincide.
  AxialFrame(const Vec3& base, const Vec3& cap);

  Vec3 to_local(const Vec3& v) const { return {dot(v, x_axis_), dot(v, y_axis_), dot(v, axis_)}; }
  // The ray's origin and direction in the frame.
  void localize(const Ray& ray, Vec3& origin, Vec3& direction) const {
    origin = to_local(ray.origin - base_);
    direction = to_local(ray.direction);
  }
  // Distance to the plane z = height_of_cap along the local ray when it meets that plane
  // within radius of the axis; false otherwise (a ray parallel to the cap never hits it).
  static bool cap_distance(const Vec3& origin, const Vec3& direction, double z, double radius, double& t);

  // Where a world point lies about the axis: distance r, angle phi in [0, 2π) from x_axis,
  // the unit radial direction and the tangent (counter-clockwise about +axis).
  struct Around {
    Vec3 local;
    double r, phi;
    Vec3 radial, tangent;
  };
  Around around(const Vec3& point) const;

  // The unit direction at angle phi about the axis, from x_axis toward y_axis.
  Vec3 radial(double phi) const { return x_axis_ * std::cos(phi) + y_axis_ * std::sin(phi); }
  // Area sampling of an end disc: a uniform point (u on the unit square) of the disc of this
  // radius about the axis at centre (the base or the cap point), facing away from the body (+axis
  // at the cap, −axis at the base). Leaves sample.pdf to the caller.
  void sample_end_disc(const Vec3& centre, bool cap, double radius, const Vec2& u,
                       SurfaceSample& sample) const;

  const Vec3& base() const { return base_; }
  const Vec3& axis() const { return axis_; }      // unit, base to cap
  const Vec3& x_axis() const { return x_axis_; }  // with y_axis, orthonormal_basis(axis)
  const Vec3& y_axis() const { return y_axis_; }
  double height() const { return height_; }

 private:
  Vec3 base_;
  Vec3 axis_;
  Vec3 x_axis_;
  Vec3 y_axis_;
  double height_;
};

}  // namespace candela
