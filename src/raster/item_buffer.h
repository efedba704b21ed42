// Item buffers (000 §6.4; Weghorst, Hooper and Greenberg 1984): the id of the nearest triangle
// at every pixel centre, drawn by the scanline rasterizer with its depth test. The hemicube
// (Cohen and Greenberg 1985) keeps "only the identity of the patch" per cell, no intensity.
//
// Triangles are given in world space with any 4×4 clip_from_world matrix (OpenGL clip space,
// as Camera::view_projection and hemicube_view_projection make); both windings are drawn (a
// caller that wants back faces culled does so itself). Pixel, coverage and depth conventions
// are the Rasterizer's.
#pragma once

#include <Eigen/Dense>
#include <cstdint>
#include <span>
#include <vector>

#include "geometry/triangle_mesh.h"
#include "math/vector.h"
#include "raster/rasterizer.h"

namespace candela {

class ItemBuffer {
 public:
  static constexpr uint32_t kNoItem = 0xFFFFFFFFu;  // background: no triangle covers the pixel

  // Throws std::invalid_argument for a width or height below 1. Starts cleared.
  ItemBuffer(int width, int height);

  // Limits drawing to x0 ≤ x < x1, y0 ≤ y < y1 (e.g. the half of a hemicube side face above
  // the surface) and clears; pixels outside it stay kNoItem. Throws std::invalid_argument
  // for a region outside the image.
  void set_region(int x0, int y0, int x1, int y1);
  void clear();  // every id to kNoItem, every depth to +∞

  // Draws one triangle with the given id: pixels where it is the nearest so far take the id.
  void draw(const Eigen::Matrix4d& clip_from_world, const Vec3& p0, const Vec3& p1, const Vec3& p2,
            uint32_t id);
  // Draws every triangle of the mesh, triangle i with ids[i] (empty: with id i). Each position is
  // transformed once. The mesh must be valid (TriangleMesh::validate: indices in range), which
  // is not checked here. Throws std::invalid_argument when ids is neither empty nor one per
  // triangle.
  void draw(const Eigen::Matrix4d& clip_from_world, const TriangleMesh& mesh,
            std::span<const uint32_t> ids = {});

  // The id at pixel (x, y) (kNoItem where nothing was drawn); throws std::out_of_range outside
  // the image.
  uint32_t at(int x, int y) const;
  // The ndc depth of what is seen at (x, y) inside the region, +∞ where nothing was drawn.
  double depth_at(int x, int y) const { return rasterizer_.depth_at(x, y); }
  const std::vector<uint32_t>& ids() const { return ids_; }  // row by row, width × height
  const RasterStatistics& statistics() const { return rasterizer_.statistics(); }
  void reset_statistics() { rasterizer_.reset_statistics(); }
  int width() const { return rasterizer_.width(); }
  int height() const { return rasterizer_.height(); }

 private:
  void draw_clip(const Eigen::Vector4d& a, const Eigen::Vector4d& b, const Eigen::Vector4d& c, uint32_t id);

  Rasterizer rasterizer_;
  std::vector<uint32_t> ids_;
  std::vector<Eigen::Vector4d> clip_positions_;  // scratch for mesh draws, kept between calls
};

}  // namespace candela
