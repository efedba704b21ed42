// Uniform grid: the scene box cut into L×M×N equal voxels, walked voxel by voxel with the 3D-DDA
// (000 §5.7.2 "subdivizare spațială uniformă"; 001 "DDA 3D"; Amanatides & Woo 1987, "A Fast
// Voxel Traversal Algorithm for Ray Tracing").
//
// Parameter grid.density (default 3): the voxel count is about density × the number of bounded
// primitives (Cleary & Wyvill 1988), with voxels as cubic as possible:
//   n_axis = round(extent_axis × cbrt(density × N / volume)), clamped to [1, 512].
// An axis whose extent would give fewer than half a voxel (a flat scene has a zero extent) gets
// one voxel and the others share the budget (square root over two axes, the extent over one).
//
// Build: every voxel lists (compact offsets + indices, ascending) the primitives whose bounds
// come within a small margin of it (accel/subdivision.h), filled in parallel. Unbounded
// primitives (planes) sit in a separate list tested on every ray.
//
// Traversal: the ray is clipped to the grid box, then each voxel's primitives are tested once
// per ray (mailbox). A hit lying beyond the current voxel may not be the nearest (000 §5.7.2),
// so it is kept and the walk goes on; it stops at the first voxel whose exit distance is at
// least the best hit so far. Results are identical to the brute-force list (accelerator.h).
#pragma once

#include <array>
#include <cstddef>
#include <span>
#include <vector>

#include "accel/accelerator.h"
#include "math/bounds.h"

namespace candela {

class UniformGrid final : public Accelerator {
 public:
  static constexpr int kMaxResolution = 512;

  // Throws std::invalid_argument unless density is finite and positive.
  explicit UniformGrid(double density = 3.0);

  void build(std::span<const Primitive> primitives) override;
  bool intersect(const Ray& ray, Intersection& intersection) const override;
  bool occluded(const Ray& ray) const override;
  std::string_view name() const override { return "grid"; }
  AcceleratorReport report() const override;

  // The voxels per axis for count bounded primitives whose bounds have the given extent (see
  // the file comment); {0, 0, 0} when count is 0.
  static std::array<int, 3> resolution_for(const Vec3& extent, std::size_t count, double density);

  // Inspection (tests, reports).
  const std::array<int, 3>& resolution() const { return resolution_; }
  const Bounds3& grid_bounds() const { return bounds_; }  // the scene bounds grown by the margin
  // The voxel holding a point (clamped to the grid); the grid must not be empty.
  std::array<int, 3> voxel_of(const Vec3& point) const;
  std::span<const uint32_t> voxel_primitives(const std::array<int, 3>& voxel) const;

 private:
  int cell_of(double coordinate, int axis) const;
  double boundary(int axis, int cell) const { return bounds_.lower[axis] + cell * cell_size_[axis]; }
  std::size_t voxel_index(const std::array<int, 3>& voxel) const {
    return (static_cast<std::size_t>(voxel[2]) * resolution_[1] + voxel[1]) * resolution_[0] + voxel[0];
  }
  // The 3D-DDA: calls visit(primitives of the voxel, t at which the ray leaves it) for each
  // voxel the ray crosses within (ray.t_min, t_max), in order, until visit returns true.
  template <typename Visit>
  void walk(const Ray& ray, double t_max, Visit&& visit) const;

  double density_;
  std::span<const Primitive> primitives_;
  std::vector<uint32_t> unbounded_;
  std::array<int, 3> resolution_{0, 0, 0};
  Bounds3 bounds_;
  double margin_ = 0;
  Vec3 cell_size_;
  Vec3 inverse_cell_size_;
  std::vector<uint32_t> offsets_;  // voxel v holds indices_[offsets_[v], offsets_[v + 1])
  std::vector<uint32_t> indices_;
};

}  // namespace candela
