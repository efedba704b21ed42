#include "accel/uniform_grid.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "accel/subdivision.h"

namespace candela {

UniformGrid::UniformGrid(double density) : density_(density) {
  if (!(density > 0) || !std::isfinite(density))
    throw std::invalid_argument("grid density must be a positive number");
}

std::array<int, 3> UniformGrid::resolution_for(const Vec3& extent, std::size_t count, double density) {
  if (count == 0) return {0, 0, 0};
  std::array<int, 3> resolution{1, 1, 1};
  std::array<bool, 3> active{};
  for (int axis = 0; axis < 3; ++axis) active[axis] = extent[axis] > 0;
  const double budget = density * static_cast<double>(count);
  for (;;) {
    int axes = 0;
    double measure = 1;  // volume, area or length of the active axes
    for (int axis = 0; axis < 3; ++axis) {
      if (!active[axis]) continue;
      ++axes;
      measure *= extent[axis];
    }
    if (axes == 0) break;
    const double ratio = budget / measure;
    const double scale = axes == 3 ? std::cbrt(ratio) : (axes == 2 ? std::sqrt(ratio) : ratio);
    // An axis that would round to no voxel at all is flat: one voxel, the budget to the others.
    bool dropped = false;
    for (int axis = 0; axis < 3; ++axis) {
      if (active[axis] && extent[axis] * scale < 0.5) {
        active[axis] = false;
        dropped = true;
      }
    }
    if (dropped) continue;
    for (int axis = 0; axis < 3; ++axis) {
      if (!active[axis]) continue;
      const double cells = std::round(extent[axis] * scale);  // may be +inf for a tiny measure
      resolution[axis] = static_cast<int>(std::clamp(cells, 1.0, static_cast<double>(kMaxResolution)));
    }
    break;
  }
  return resolution;
}

int UniformGrid::cell_of(double coordinate, int axis) const {
  const double cell = std::floor((coordinate - bounds_.lower[axis]) * inverse_cell_size_[axis]);
  if (!(cell > 0)) return 0;  // NaN included
  return static_cast<int>(std::min(cell, static_cast<double>(resolution_[axis] - 1)));
}

std::array<int, 3> UniformGrid::voxel_of(const Vec3& point) const {
  return {cell_of(point.x, 0), cell_of(point.y, 1), cell_of(point.z, 2)};
}

std::span<const uint32_t> UniformGrid::voxel_primitives(const std::array<int, 3>& voxel) const {
  const std::size_t index = voxel_index(voxel);
  return std::span<const uint32_t>(indices_).subspan(offsets_[index], offsets_[index + 1] - offsets_[index]);
}

void UniformGrid::build(std::span<const Primitive> primitives) {
  primitives_ = primitives;
  offsets_.clear();
  indices_.clear();
  subdivision::PrimitiveSplit split = subdivision::split_primitives(primitives);
  unbounded_ = std::move(split.unbounded);
  resolution_ = resolution_for(split.scene.diagonal(), split.bounded.size(), density_);
  if (split.bounded.empty()) {
    bounds_ = Bounds3{};
    return;
  }
  margin_ = split.margin;
  bounds_ = subdivision::grown(split.scene, margin_);
  for (int axis = 0; axis < 3; ++axis) {
    const double extent = bounds_.upper[axis] - bounds_.lower[axis];
    cell_size_[axis] = extent / resolution_[axis];
    inverse_cell_size_[axis] = resolution_[axis] / extent;
  }
  const std::size_t voxels = static_cast<std::size_t>(resolution_[0]) * resolution_[1] * resolution_[2];

  // The voxel range of each bounded primitive, its bounds grown by the margin.
  const std::size_t count = split.bounded.size();
  std::vector<std::array<int, 6>> ranges(count);
  tbb::parallel_for(std::size_t{0}, count, [&](std::size_t i) {
    const Bounds3 bounds = subdivision::grown(split.bounds[split.bounded[i]], margin_);
    ranges[i] = {cell_of(bounds.lower.x, 0), cell_of(bounds.lower.y, 1), cell_of(bounds.lower.z, 2),
                 cell_of(bounds.upper.x, 0), cell_of(bounds.upper.y, 1), cell_of(bounds.upper.z, 2)};
  });
  const auto for_each_voxel = [&](const std::array<int, 6>& range, auto&& visit) {
    for (int z = range[2]; z <= range[5]; ++z)
      for (int y = range[1]; y <= range[4]; ++y)
        for (int x = range[0]; x <= range[3]; ++x) visit(voxel_index({x, y, z}));
  };

  // Counting sort into compact arrays: count, prefix sum, scatter, then sort each voxel's list
  // so that the result does not depend on the thread schedule.
  std::vector<std::atomic<uint32_t>> cursor(voxels);  // value-initialised to 0
  tbb::parallel_for(std::size_t{0}, count, [&](std::size_t i) {
    for_each_voxel(ranges[i],
                   [&](std::size_t voxel) { cursor[voxel].fetch_add(1, std::memory_order_relaxed); });
  });
  offsets_.resize(voxels + 1);
  uint64_t total = 0;
  for (std::size_t voxel = 0; voxel < voxels; ++voxel) {
    offsets_[voxel] = static_cast<uint32_t>(total);
    total += cursor[voxel].load(std::memory_order_relaxed);
    if (total > std::numeric_limits<uint32_t>::max())
      throw std::length_error("uniform grid: more than 2^32 primitive references");
    cursor[voxel].store(offsets_[voxel], std::memory_order_relaxed);
  }
  offsets_[voxels] = static_cast<uint32_t>(total);
  indices_.resize(total);
  tbb::parallel_for(std::size_t{0}, count, [&](std::size_t i) {
    for_each_voxel(ranges[i], [&](std::size_t voxel) {
      indices_[cursor[voxel].fetch_add(1, std::memory_order_relaxed)] = split.bounded[i];
    });
  });
  tbb::parallel_for(std::size_t{0}, voxels, [&](std::size_t voxel) {
    std::sort(indices_.begin() + offsets_[voxel], indices_.begin() + offsets_[voxel + 1]);
  });
}

template <typename Visit>
void UniformGrid::walk(const Ray& ray, double t_max, Visit&& visit) const {
  if (offsets_.empty()) return;
  Ray clipped = ray;
  clipped.t_max = t_max;
  double t_enter = 0, t_exit = 0;
  if (!bounds_.intersect(clipped, t_enter, t_exit)) return;
  // Amanatides & Woo: the start voxel, then per axis the step and the t of the next boundary.
  // The boundary t are recomputed from the cell index at each step (no drift).
  const Vec3 start = ray.at(t_enter);
  std::array<int, 3> cell{};
  std::array<int, 3> step{};
  std::array<int, 3> stop{};
  std::array<double, 3> next{};
  for (int axis = 0; axis < 3; ++axis) {
    cell[axis] = cell_of(start[axis], axis);
    const double direction = ray.direction[axis];
    if (direction > 0) {
      step[axis] = 1;
      stop[axis] = resolution_[axis];
      next[axis] = (boundary(axis, cell[axis] + 1) - ray.origin[axis]) / direction;
    } else if (direction < 0) {
      step[axis] = -1;
      stop[axis] = -1;
      next[axis] = (boundary(axis, cell[axis]) - ray.origin[axis]) / direction;
    } else {
      step[axis] = 0;
      stop[axis] = -1;
      next[axis] = kInfinity;
    }
  }
  for (;;) {
    const int axis = next[0] < next[1] ? (next[0] < next[2] ? 0 : 2) : (next[1] < next[2] ? 1 : 2);
    const double voxel_exit = next[axis];
    if (visit(voxel_primitives(cell), voxel_exit)) return;
    if (voxel_exit >= t_exit) return;  // the ray leaves the grid (or ends) in this voxel
    cell[axis] += step[axis];
    if (cell[axis] == stop[axis]) return;
    next[axis] =
        (boundary(axis, cell[axis] + (step[axis] > 0 ? 1 : 0)) - ray.origin[axis]) / ray.direction[axis];
  }
}

bool UniformGrid::intersect(const Ray& ray, Intersection& intersection) const {
  subdivision::NearestHit nearest(primitives_, ray, intersection);
  for (uint32_t index : unbounded_) nearest.test(index);
  subdivision::RayMailbox mailbox;
  walk(ray, nearest.search_limit(), [&](std::span<const uint32_t> voxel, double voxel_exit) {
    for (uint32_t index : voxel)
      if (mailbox.insert(index)) nearest.test(index);
    // 000 §5.7.2: the best hit is final once it lies inside the part of the ray walked so far.
    return nearest.found() && nearest.best_t() <= voxel_exit;
  });
  return nearest.found();
}

bool UniformGrid::occluded(const Ray& ray) const {
  for (uint32_t index : unbounded_)
    if (primitives_[index].shape->occluded(ray)) return true;
  bool hit = false;
  subdivision::RayMailbox mailbox;
  walk(ray, ray.t_max, [&](std::span<const uint32_t> voxel, double) {
    for (uint32_t index : voxel)
      if (mailbox.insert(index) && primitives_[index].shape->occluded(ray)) return hit = true;
    return false;
  });
  return hit;
}

AcceleratorReport UniformGrid::report() const {
  std::size_t non_empty = 0;
  for (std::size_t voxel = 0; voxel + 1 < offsets_.size(); ++voxel)
    if (offsets_[voxel + 1] > offsets_[voxel]) ++non_empty;
  const std::size_t voxels = offsets_.empty() ? 0 : offsets_.size() - 1;
  AcceleratorReport report;
  report.figures = {
      {"voxels", static_cast<double>(voxels)},
      {"L", static_cast<double>(resolution_[0])},
      {"M", static_cast<double>(resolution_[1])},
      {"N", static_cast<double>(resolution_[2])},
      {"non-empty voxels", static_cast<double>(non_empty)},
      {"primitives per non-empty voxel",
       non_empty == 0 ? 0.0 : static_cast<double>(indices_.size()) / static_cast<double>(non_empty)},
      {"references", static_cast<double>(indices_.size())},
      {"unbounded", static_cast<double>(unbounded_.size())},
  };
  report.bytes = (offsets_.capacity() + indices_.capacity() + unbounded_.capacity()) * sizeof(uint32_t);
  return report;
}

}  // namespace candela
