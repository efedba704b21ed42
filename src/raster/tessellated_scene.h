// A scene as triangles, for the rasterizer (SPEC §9) and the Gouraud display of radiosity:
// every primitive tessellated by Shape::tessellate, vertex normals averaged from the adjacent
// face normals of the same object with a crease angle (000 §3.2, §3.2.1: a real edge keeps two
// normals at its vertices) — triangle meshes keep their own normals (smooth, from the file, or
// flat) — and per triangle the primitive, object and material it came from.
#pragma once

#include <Eigen/Dense>
#include <array>
#include <cstdint>
#include <vector>

#include "geometry/triangle_mesh.h"
#include "scene/scene.h"

namespace candela {

struct TessellatedScene {
  // Corner data, three entries per triangle (triangle t owns corners 3t, 3t+1, 3t+2).
  std::vector<Vec3> corner_positions;         // world
  std::vector<Vec3> corner_object_positions;  // the shape's own coordinates (solid textures)
  std::vector<Vec3> corner_normals;           // unit (or zero)
  std::vector<Vec2> corner_uvs;               // the shape's parametrisation
  // Per triangle.
  std::vector<Vec3> face_normals;  // unit, counter-clockwise: the shape's geometric normal side
  std::vector<uint32_t> primitives;
  std::vector<uint32_t> materials;
  std::vector<uint32_t> objects;

  std::size_t triangle_count() const { return primitives.size(); }
};

struct TessellationRequest {
  // The most segments a full turn gets (TessellationSettings::segments). With a view (below),
  // a curved shape gets only as many as give edges of about one pixel on screen, at least 8.
  int max_segments = 32;
  // > 0 (radiosity): instead of the view, each curved shape gets the fewest segments
  // (at least 6, at most max_segments) whose chords stray at most this far from its surface.
  double chord_tolerance = 0;
  double crease_angle_degrees = 60;
  // Where unbounded shapes (planes) are cut.
  Bounds3 clip;
  // The view: the clip_from_world matrix and image width, for on-screen sizes (none: every
  // curved shape gets max_segments), and the eye, toward which planes are refined.
  bool has_view = false;
  Eigen::Matrix4d clip_from_world = Eigen::Matrix4d::Identity();
  int image_width = 0;
  Vec3 eye;
};

// Degenerate (zero-area) triangles are dropped. A plane's few big triangles are split in halves
// until each edge is shorter than a tenth of its distance to the eye (and at most 20 levels),
// so flat and Gouraud shading have vertices where the light changes.
TessellatedScene tessellate_scene(const Scene& scene, const TessellationRequest& request);

// The number of triangles tessellate_scene gives for the request, counted a primitive at
// a time without holding them: what a method's memory estimate needs before it tessellates.
std::size_t tessellated_triangle_count(const Scene& scene, const TessellationRequest& request);

// The bytes a TessellatedScene keeps per triangle (its corners' four arrays and its own four).
inline constexpr std::size_t kTessellatedTriangleBytes =
    3 * (3 * sizeof(Vec3) + sizeof(Vec2)) + sizeof(Vec3) + 3 * sizeof(uint32_t);

// The box that holds the scene's bounded shapes, the eye, and the point of every plane nearest
// the eye, grown `margin` times its size about its centre: where planes are cut.
Bounds3 raster_clip_box(const Scene& scene, const Vec3& eye, double margin);

}  // namespace candela
