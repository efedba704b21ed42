// Triangle meshes baked into world space, and the "triangle" shape: one triangle of a mesh,
// intersected with the watertight test of Woop, Benthin and Wald 2013 ("Watertight Ray/Triangle
// Intersection", JCGT 2(1)).
//
// Conventions:
// - Winding: the geometric normal is normalize(cross(p1 - p0, p2 - p0)), i.e. counter-clockwise
//   corners (seen from outside) give an outward normal. The test itself is two-sided.
// - Shading normal: the barycentric interpolation of the corner normals (normalised) when the
//   mesh has them, else the geometric normal. It is not flipped to the geometric side.
// - uv: barycentric interpolation of the corner uvs; without them the corners get (0,0), (1,0),
//   (1,1) (as pbrt), so that uv = (b1 + b2, b2).
// - dpdu/dpdv: from the uv parameterisation (pbrt's formula); when the uv determinant is
//   degenerate, an orthonormal basis around the geometric normal with dpdu x dpdv = normal.
// - Zero-area triangles (cross(p1 - p0, p2 - p0) exactly zero) never hit; make_triangles skips
//   them and counts them.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "geometry/shape.h"
#include "math/lanes.h"
#include "math/transform.h"

namespace candela {

// The corner uvs of a triangle whose mesh has none (as pbrt), so that uv = (b1 + b2, b2).
inline constexpr std::array<Vec2, 3> kDefaultCornerUvs{Vec2{0, 0}, Vec2{1, 0}, Vec2{1, 1}};

struct TriangleMesh {
  std::vector<Vec3> positions;
  std::vector<std::array<uint32_t, 3>> triangles;  // indices into positions
  // Per-corner shading normals, one entry per triangle; empty = flat shading.
  std::vector<std::array<Vec3, 3>> corner_normals;
  // Per-corner uvs, one entry per triangle; empty = (0,0), (1,0), (1,1) at the three corners.
  std::vector<std::array<Vec2, 3>> corner_uvs;

  // Throws std::invalid_argument when an index is out of range, a corner array is neither
  // empty nor one entry per triangle, or a position is not finite.
  void validate() const;

  // cross(p1 - p0, p2 - p0): twice the area times the (counter-clockwise) unit normal.
  Vec3 face_cross(std::size_t triangle) const;
  // Zero (or non-finite) area: such a triangle is never hit.
  bool is_degenerate(std::size_t triangle) const;
  Bounds3 bounds() const;
  Bounds3 triangle_bounds(std::size_t triangle) const;

  // Bakes object_to_world into the mesh: positions as points, corner normals by the inverse
  // transpose (renormalised; zero normals stay zero). A transform that mirrors (negative
  // determinant) also reverses every triangle's winding so that the geometric normal keeps
  // pointing the way it did (outward stays outward).
  void transform(const Transform& object_to_world);
};

// How a mesh is shaded: flat (geometric normals only) or smooth (corner normals, from the file
// or computed by compute_corner_normals with a crease angle).
enum class NormalMode { flat, smooth };

// Fills mesh.corner_normals: each corner gets the normalised sum of the area-weighted face
// normals of every triangle around its vertex whose face normal lies within
// crease_angle_degrees of this triangle's own face normal (the triangle itself always counts).
// Vertices are welded by exact position first, so duplicated OBJ vertices are smoothed across.
// Crease 0 gives flat normals; crease >= 180 averages everything around a vertex. Corners of
// degenerate triangles get a zero normal (such triangles are never hit). Throws
// std::invalid_argument for a negative or NaN crease angle or an invalid mesh.
void compute_corner_normals(TriangleMesh& mesh, double crease_angle_degrees);

// The result of the watertight test: the distance and the barycentric weights of p0, p1, p2.
struct TriangleIntersection {
  double t = 0;
  double b0 = 0, b1 = 0, b2 = 0;
};

// Woop, Benthin, Wald 2013, in double precision (edge functions recomputed in long double when
// one is exactly zero, as the paper falls back from float to double). Accepts hits with
// ray.t_min < t < ray.t_max only; two-sided; a zero-determinant (edge-on or degenerate)
// triangle is missed. Watertight: a ray crossing a shared edge or vertex hits at least one of
// the triangles that share it.
bool intersect_triangle(const Ray& ray, const Vec3& p0, const Vec3& p1, const Vec3& p2,
                        TriangleIntersection& result);

// Fills hit from a watertight hit (found, from intersect_triangle with the triangle's corners
// p0, p1, p2, which must be the mesh's positions of that triangle) exactly as
// MeshTriangle::intersect does: it is the code MeshTriangle::intersect runs after its test, so
// an accelerator that already holds the corners gets a bit-identical SurfaceHit.
void fill_triangle_hit(const TriangleMesh& mesh, std::size_t triangle, const Vec3& p0, const Vec3& p1,
                       const Vec3& p2, const TriangleIntersection& found, SurfaceHit& hit);

// The per-ray part of the watertight test (the dominant axis and the shear), computed once per
// ray by the accelerators; WatertightRay::distance then costs one division per triangle and
// gives a t bit-identical to intersect_triangle's.
struct WatertightRay {
  Vec3 origin;
  int kx, ky, kz;
  double sx, sy, sz;
  double t_min, t_max;

  // Inline (below): the accelerators make one per ray, and the call cost as much as the
  // arithmetic; it has only divisions and comparisons, nothing a target with FMA could contract,
  // so the BVH's AVX2 and AVX-512 copies compute the same bits.
  explicit WatertightRay(const Ray& ray);
  // Edge functions u, v, w (weights of p0, p1, p2 times det) and det = u + v + w; false when
  // the ray misses the triangle's interior (or is edge-on).
  bool edges(const Vec3& p0, const Vec3& p1, const Vec3& p2, double& u, double& v, double& w,
             double& det) const;
  // The hit distance in (t_min, t_max), or false.
  bool distance(const Vec3& p0, const Vec3& p1, const Vec3& p2, double& t) const;
  // The hit distance in (t_min, t_max) and the barycentric weights, or false (result is then
  // left as it was): exactly intersect_triangle's result for the ray this was made from.
  bool intersect(const Vec3& p0, const Vec3& p1, const Vec3& p2, TriangleIntersection& result) const;
};

inline WatertightRay::WatertightRay(const Ray& ray) : origin(ray.origin), t_min(ray.t_min), t_max(ray.t_max) {
  // The dominant direction axis becomes z; swapping x and y when it points down keeps the
  // winding (the test is two-sided, so this only matters for bit-identical edge values).
  // Without branches: the axes change from ray to ray, and the accelerators make this for
  // every ray, so branches on them would often be mispredicted. kz is
  // max_dimension(abs(direction)): the axis of the largest magnitude, the later on a tie.
  const Vec3 magnitude = abs(ray.direction);
  const int x_over_y = magnitude.x > magnitude.y, x_over_z = magnitude.x > magnitude.z,
            y_over_z = magnitude.y > magnitude.z;
  kz = x_over_y * 2 * (1 - x_over_z) + (1 - x_over_y) * (2 - y_over_z);
  static constexpr int kNext[3] = {1, 2, 0};
  kx = kNext[kz];
  ky = kNext[kx];
  const double direction[3] = {ray.direction.x, ray.direction.y, ray.direction.z};
  const int swap = (kx ^ ky) & -static_cast<int>(direction[kz] < 0);
  kx ^= swap;
  ky ^= swap;
  // Shear so that the ray becomes the +z axis (the z scale is applied later, only for t).
  // The three quotients in one vector division (each lane rounded as its scalar division).
  const Double4 numerator = {direction[kx], direction[ky], 1.0, 1.0};
  const Double4 quotient = numerator / direction[kz];
  sx = quotient[0];
  sy = quotient[1];
  sz = quotient[2];
}

class MeshTriangle final : public Shape {
 public:
  // Throws std::invalid_argument when mesh is null, triangle_index is out of range, a corner
  // index is out of range or a corner array has the wrong size. Degenerate triangles are
  // accepted here (and never hit); make_triangles skips them.
  MeshTriangle(std::shared_ptr<const TriangleMesh> mesh, uint32_t triangle_index);

  bool intersect(const Ray& ray, SurfaceHit& hit) const override;
  bool occluded(const Ray& ray) const override;
  Bounds3 bounds() const override;
  std::string_view type_name() const override { return "triangle"; }
  // Its one triangle (none when degenerate), in the mesh's winding and with the mesh's corner
  // uvs (or kDefaultCornerUvs); the mesh's corner normals are not copied (Shape::tessellate).
  void tessellate(const TessellationSettings& settings, TriangleMesh& mesh) const override;
  // Sampling (SPEC §12): uniform in area (barycentrics b0 = 1 − √u.x, b1 = u.y √u.x), the
  // normal the geometric one intersect reports; a degenerate triangle has area 0 and is not
  // sampled.
  double area() const override;
  bool sample_area(const Vec2& u, SurfaceSample& sample) const override;
  double pdf_area(const SurfaceHit& hit) const override;

  const TriangleMesh& mesh() const { return *mesh_; }
  const std::shared_ptr<const TriangleMesh>& shared_mesh() const { return mesh_; }
  uint32_t triangle_index() const { return index_; }

 private:
  std::shared_ptr<const TriangleMesh> mesh_;
  uint32_t index_;
  bool degenerate_;
};

// For each triangle, whether it repeats an earlier, non-degenerate one: the same three corner
// positions in the same cyclic order (the same surface facing the same way; the reversed
// winding faces the other way and is not a repeat). Degenerate triangles are never repeats.
// O(n log n): the corners are hashed and sorted.
std::vector<bool> repeated_triangles(const TriangleMesh& mesh);

// One MeshTriangle per non-degenerate triangle, in triangle order. When skipped_degenerate is
// given it receives the number of degenerate triangles left out (the loader warns about them).
// When merged_duplicates is given, repeated triangles (repeated_triangles) are left out too and
// counted there: tens of thousands of copies of one triangle, which a ray must all test to find
// the lowest index among equal distances, made a 180 KB OBJ take most of an hour to bench;
// the first copy is kept and the triangle indices stay those of the mesh.
// Throws std::invalid_argument when mesh is null or invalid (see TriangleMesh::validate).
std::vector<std::unique_ptr<Shape>> make_triangles(std::shared_ptr<const TriangleMesh> mesh,
                                                   std::size_t* skipped_degenerate = nullptr,
                                                   std::size_t* merged_duplicates = nullptr);

}  // namespace candela
