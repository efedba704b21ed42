#pragma once

#include "geometry/shape.h"

namespace candela {

// A parallelogram: the points corner + u·edge_u + v·edge_v for (u, v) in [0, 1]², which are
// also its parametric uv (000 §4.1.2): dpdu = edge_u, dpdv = edge_v, and the normal is
// edge_u × edge_v, normalised. Like the other flat shapes both sides are hit and the geometric
// normal is the declared one; edges and corners belong to the quad; a ray in its plane misses.
class Quad final : public Shape {
 public:
  // Throws std::invalid_argument for non-finite input or parallel (or zero) edges.
  Quad(const Vec3& corner, const Vec3& edge_u, const Vec3& edge_v);

  bool intersect(const Ray& ray, SurfaceHit& hit) const override;
  bool occluded(const Ray& ray) const override;
  Bounds3 bounds() const override;
  std::string_view type_name() const override { return "quad"; }
  // Two triangles, corner → corner + edge_u → opposite corner and back by corner + edge_v.
  void tessellate(const TessellationSettings& settings, TriangleMesh& mesh) const override;

  const Vec3& corner() const { return corner_; }
  const Vec3& edge_u() const { return edge_u_; }
  const Vec3& edge_v() const { return edge_v_; }
  const Vec3& normal() const { return normal_; }
  // Sampling (SPEC §12): uniform in area, the point corner + u.x·edge_u + u.y·edge_v.
  double area() const override { return area_; }
  bool sample_area(const Vec2& u, SurfaceSample& sample) const override;
  double pdf_area(const SurfaceHit& hit) const override;
  // Seen from a point within two diagonals of its centre: (u, v) drawn from the bilinear density
  // through the solid-angle density |cos θ|/d² at the four corners (Hart et al. 2020's warp):
  // where uniform area sampling puts as many points on the far half as on the near one, most
  // points go where the quad subtends most. Farther away, uniform in area. No trigonometry
  // (exact spherical-rectangle sampling, Ureña et al. 2013, has four acos per point and cost the
  // Cornell box 15 % of its render time).
  bool sample_from(const Vec3& reference, const Vec2& u, SurfaceSample& sample) const override;
  double pdf_from(const Vec3& reference, const SurfaceHit& hit) const override;

 private:
  // The hit distance and (u, v), or infinity for none.
  double nearest_t(const Ray& ray, double& u, double& v) const;
  // How sample_from draws from a reference point: its height over the plane, and whether it is
  // near enough for the warp, with the corners' weights.
  struct CornerWeights {
    double height = 0;
    bool warped = false;
    double w[4] = {};
  };
  bool seen_from(const Vec3& reference, CornerWeights& weights) const;  // false: in the plane
  // The solid-angle density of the point (u, v).
  double solid_angle_pdf(const Vec3& reference, const Vec2& uv, const Vec3& position,
                         const CornerWeights& weights) const;
  Vec3 corner_, edge_u_, edge_v_, normal_;
  // Rows of the inverse of [edge_u edge_v] restricted to the plane: u = dual_u·(p − corner).
  Vec3 dual_u_, dual_v_;
  double area_;
  // Squared distance from the centre within which sample_from warps (two mean diagonals).
  double warp_distance_squared_;
};

}  // namespace candela
