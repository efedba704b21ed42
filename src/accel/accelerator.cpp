#include "accel/accelerator.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <array>
#include <bit>

#include "geometry/triangle_mesh.h"
#include "util/hash.h"

namespace candela {

std::vector<uint32_t> reportable_primitives(std::span<const Primitive> primitives) {
  const std::size_t count = primitives.size();
  // A triangle's corner k (only called for primitives hashed as triangles).
  const auto corner = [&](uint32_t i, int k) -> const Vec3& {
    const auto& triangle = static_cast<const MeshTriangle&>(*primitives[i].shape);
    return triangle.mesh().positions[triangle.mesh().triangles[triangle.triangle_index()][k]];
  };
  std::vector<uint8_t> keep(count, 1);
  // Per primitive: the hash of its triangle's corner bits, never 0; 0 for any other shape.
  std::vector<std::pair<uint64_t, uint32_t>> hashes(count);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, 4096),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t i = range.begin(); i < range.end(); ++i) {
                        const auto index = static_cast<uint32_t>(i);
                        hashes[i] = {0, index};
                        const auto* triangle = dynamic_cast<const MeshTriangle*>(primitives[i].shape);
                        if (!triangle) continue;
                        if (triangle->mesh().is_degenerate(triangle->triangle_index())) {
                          keep[i] = 0;
                          continue;
                        }
                        uint64_t hash = 1;
                        for (int k = 0; k < 3; ++k)
                          for (int axis = 0; axis < 3; ++axis)
                            hash = mix64(hash ^ std::bit_cast<uint64_t>(corner(index, k)[axis]));
                        hashes[i].first = hash | 1;
                      }
                    });
  tbb::parallel_sort(hashes.begin(), hashes.end());
  const auto same = [&](uint32_t a, uint32_t b) {
    for (int k = 0; k < 3; ++k)
      for (int axis = 0; axis < 3; ++axis)
        if (std::bit_cast<uint64_t>(corner(a, k)[axis]) != std::bit_cast<uint64_t>(corner(b, k)[axis]))
          return false;
    return true;
  };
  // In a run of equal hashes (index order within it), the first of each corner set stays.
  std::vector<uint32_t> distinct;
  for (std::size_t begin = 0; begin < count;) {
    std::size_t end = begin + 1;
    while (end < count && hashes[end].first == hashes[begin].first) ++end;
    if (hashes[begin].first != 0 && end - begin > 1) {
      distinct.clear();
      for (std::size_t i = begin; i < end; ++i) {
        const uint32_t index = hashes[i].second;
        if (std::any_of(distinct.begin(), distinct.end(), [&](uint32_t d) { return same(d, index); }))
          keep[index] = 0;
        else
          distinct.push_back(index);
      }
    }
    begin = end;
  }
  hashes = {};
  std::vector<uint32_t> result;
  result.reserve(count);
  for (std::size_t i = 0; i < count; ++i)
    if (keep[i]) result.push_back(static_cast<uint32_t>(i));
  return result;
}

std::string AcceleratorReport::text() const {
  std::string text;
  for (const auto& [name, value] : figures) text += fmt::format("{} {:.6g}, ", name, value);
  text += fmt::format("{:.2f} MiB", bytes / (1024.0 * 1024.0));
  return text;
}

}  // namespace candela
