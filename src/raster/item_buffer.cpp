#include "raster/item_buffer.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace candela {

namespace {

Eigen::Vector4d to_clip(const Eigen::Matrix4d& clip_from_world, const Vec3& p) {
  return clip_from_world * Eigen::Vector4d(p.x, p.y, p.z, 1);
}

}  // namespace

ItemBuffer::ItemBuffer(int width, int height)
    : rasterizer_(width, height),
      ids_(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), kNoItem) {}

void ItemBuffer::set_region(int x0, int y0, int x1, int y1) {
  rasterizer_.set_region(x0, y0, x1, y1);
  clear();
}

void ItemBuffer::clear() {
  std::fill(ids_.begin(), ids_.end(), kNoItem);
  rasterizer_.clear_depth();
}

void ItemBuffer::draw_clip(const Eigen::Vector4d& a, const Eigen::Vector4d& b, const Eigen::Vector4d& c,
                           uint32_t id) {
  // Only the clip coordinates are read (no varyings): the rest of each vertex stays unset.
  RasterVertex corners[3];
  corners[0].clip = a;
  corners[1].clip = b;
  corners[2].clip = c;
  uint32_t* ids = ids_.data();
  const int width = rasterizer_.width();
  rasterizer_.draw_triangle(corners[0], corners[1], corners[2], 0,
                            [ids, width, id](const Fragment& fragment) {
                              ids[static_cast<std::size_t>(fragment.y) * static_cast<std::size_t>(width) +
                                  static_cast<std::size_t>(fragment.x)] = id;
                              return true;
                            });
}

void ItemBuffer::draw(const Eigen::Matrix4d& clip_from_world, const Vec3& p0, const Vec3& p1, const Vec3& p2,
                      uint32_t id) {
  draw_clip(to_clip(clip_from_world, p0), to_clip(clip_from_world, p1), to_clip(clip_from_world, p2), id);
}

void ItemBuffer::draw(const Eigen::Matrix4d& clip_from_world, const TriangleMesh& mesh,
                      std::span<const uint32_t> ids) {
  if (!ids.empty() && ids.size() != mesh.triangles.size())
    throw std::invalid_argument("item buffer: " + std::to_string(ids.size()) + " ids for " +
                                std::to_string(mesh.triangles.size()) + " triangles");
  clip_positions_.resize(mesh.positions.size());
  for (std::size_t i = 0; i < mesh.positions.size(); ++i)
    clip_positions_[i] = to_clip(clip_from_world, mesh.positions[i]);
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& corner = mesh.triangles[t];
    draw_clip(clip_positions_[corner[0]], clip_positions_[corner[1]], clip_positions_[corner[2]],
              ids.empty() ? static_cast<uint32_t>(t) : ids[t]);
  }
}

uint32_t ItemBuffer::at(int x, int y) const {
  if (x < 0 || x >= width() || y < 0 || y >= height())
    throw std::out_of_range("item buffer: pixel (" + std::to_string(x) + ", " + std::to_string(y) +
                            ") is outside the image");
  return ids_[static_cast<std::size_t>(y) * static_cast<std::size_t>(width()) + static_cast<std::size_t>(x)];
}

}  // namespace candela
