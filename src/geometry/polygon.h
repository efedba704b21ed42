#pragma once

#include <array>
#include <vector>

#include "geometry/shape.h"
#include "sampling/piecewise_constant.h"

namespace candela {

// A planar simple polygon, convex or not (000 §5.6.2; edges that cross are refused): the plane test of eq.
// 5-12/5-13, then the Jordan curve test on the projection onto the coordinate plane where the polygon is
// largest, counting crossings of the +u half-axis from the hit point. A vertex on that half-axis counts as
// lying on the +v side, so a polygon's points are counted once: edges shared by two polygons of one plane
// belong to exactly one of them. A ray parallel to the plane misses. The normal is Newell's
// (counter-clockwise vertices give it by the right-hand rule); both sides are hit and the normal is not
// flipped. uv: coordinates along the first edge (u) and normal x first edge (v) from the first vertex, scaled
// so the polygon's bounding rectangle in that frame is [0,1]^2; dpdu x dpdv points along the normal.
class Polygon final : public Shape {
 public:
  explicit Polygon(std::vector<Vec3> vertices);

  bool intersect(const Ray& ray, SurfaceHit& hit) const override;
  bool occluded(const Ray& ray) const override;
  Bounds3 bounds() const override;
  std::string_view type_name() const override { return "polygon"; }
  // Ear clipping in the polygon's plane (convex or not): at most vertices - 2 triangles, all
  // counter-clockwise about the normal, on the polygon's own vertices, uv as on a hit. A vertex
  // between two collinear edges is kept (it is a corner of a neighbouring triangle) but never
  // clipped as an ear of zero area. O(vertices³) at worst, which polygons of a scene file afford.
  void tessellate(const TessellationSettings& settings, TriangleMesh& mesh) const override;
  // Sampling (SPEC §12): uniform in area over the triangles of tessellate (so convex or not),
  // one picked by its area, then a uniform point in it. area() is the sum of those triangles'
  // areas (|Newell's vector| / 2 for a simple polygon).
  double area() const override { return area_; }
  bool sample_area(const Vec2& u, SurfaceSample& sample) const override;
  double pdf_area(const SurfaceHit& hit) const override;

  const std::vector<Vec3>& vertices() const { return vertices_; }
  const Vec3& normal() const { return normal_; }

 private:
  // The hit distance, or infinity for none (a hit always has t < t_max <= infinity).
  double nearest_t(const Ray& ray) const;
  // The Jordan test on the projection (000 Figure 42).
  bool contains_projected(double u, double v) const;
  // Throws std::invalid_argument when two edges that share no vertex cross.
  void refuse_crossing_edges() const;
  std::vector<Vec3> vertices_;
  std::vector<Vec2> projected_;  // the vertices on the (u_index_, v_index_) plane
  Vec3 normal_;
  int u_index_ = 0;
  int v_index_ = 1;
  // The uv frame: origin at the first vertex, axes, and the bounding rectangle in it.
  Vec3 u_axis_;
  Vec3 v_axis_;
  Vec2 uv_lower_;
  Vec2 uv_extent_;
  Bounds3 bounds_;
  // The triangles of tessellate, chosen by area when sampling.
  std::vector<std::array<Vec3, 3>> sample_triangles_;
  Distribution1D triangle_choice_;
  double area_ = 0;
};

}  // namespace candela
