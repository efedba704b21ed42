#include "integrators/raster_method.h"

#include <fmt/format.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <stdexcept>
#include <string>

#include "camera/accumulation_buffer.h"
#include "camera/antialiasing.h"
#include "camera/sample_grid.h"
#include "integrators/direct_lighting.h"
#include "integrators/distributed_tiles.h"
#include "integrators/memory_estimate.h"
#include "raster/rasterizer.h"
#include "raster/tessellated_scene.h"
#include "scene/light_samples.h"
#include "shading/cook_torrance.h"
#include "shading/local_model.h"
#include "shading/optics.h"
#include "util/cancellation.h"
#include "util/error.h"
#include "util/progress.h"

namespace candela {

RasterSettings read_raster_settings(const JsonNode& node) {
  RasterSettings settings;
  node.expect_object();
  settings.shading = node.enumeration("shading", settings.shading, kRasterShadingNames);
  settings.segments = node.integer("segments", settings.segments, {3, 4096, false, false});
  settings.crease_angle = node.number("crease_angle", settings.crease_angle, {0, 180, false, false});
  settings.shadows = node.boolean("shadows", settings.shadows);
  node.finish();
  return settings;
}

namespace {

// Varyings of the per-pixel modes, in this order.
constexpr int kPosition = 0;         // world position (3)
constexpr int kObjectPosition = 3;   // object position (3), for solid textures
constexpr int kUv = 6;               // uv (2)
constexpr int kNormal = 8;           // vertex normal (3), phong
constexpr int kSurfaceVaryings = 8;  // position, object position, uv
constexpr int kPerLight = 4;         // dot-product mode: N·L and the specular color

// Everything the shading of one scene needs, shared by all tiles.
// "dotproduct" interpolates N·L toward one point per light, so it cannot take the sky
// (no one direction) nor more lights than the rasterizer's varyings hold.
void refuse_dot_product_scene(const RasterSettings& settings, const Scene& scene) {
  if (settings.shading != RasterShading::dot_product) return;
  if (scene.environment_light)
    throw InputError({scene.source, 0, 0, "raster.shading"},
                     "raster cannot light the scene by the environment with \"dotproduct\" shading (it "
                     "interpolates N·L toward one point per light); use \"phong\" or \"gouraud\"");
  if (kSurfaceVaryings + kPerLight * static_cast<int>(scene.emitter_count()) > kMaxVaryings)
    throw InputError({scene.source, 0, 0, "raster.shading"},
                     "\"dotproduct\" interpolates " + std::to_string(kPerLight) +
                         " values per light and supports at most " +
                         std::to_string((kMaxVaryings - kSurfaceVaryings) / kPerLight) +
                         " lights (the scene has " + std::to_string(scene.emitter_count()) +
                         ", its emissive surfaces included)");
}

class RasterShader {
 public:
  RasterShader(const Scene& scene, const TessellatedScene& triangles, const RasterSettings& settings)
      : scene_(scene),
        triangles_(triangles),
        settings_(settings),
        perspective_(scene.camera->type_name() == "perspective"),
        eye_(scene.camera->eye_position()),
        view_direction_(scene.camera->view_direction()) {
    refuse_dot_product_scene(settings_, scene);
  }

  int varying_count() const {
    switch (settings_.shading) {
      case RasterShading::flat:
        return 0;
      case RasterShading::gouraud:
        return 3;
      case RasterShading::phong:
        return kNormal + 3;
      case RasterShading::dot_product:
        return kSurfaceVaryings + kPerLight * static_cast<int>(scene_.emitter_count());
    }
    return 0;
  }

  // The unit vector toward the viewer from p.
  Vec3 toward_viewer(const Vec3& p) const { return perspective_ ? normalize(eye_ - p) : -view_direction_; }

  // A point of a triangle moved onto the primitive's true surface along the face normal: a
  // curved shape's triangles lie inside it (their vertices on it), and a shadow ray leaving
  // from inside would be stopped by the shape itself. Planar shapes are hit at t = 0: kept.
  Vec3 on_surface(uint32_t triangle, const Vec3& p) const {
    const std::size_t c = 3 * std::size_t(triangle);
    const Vec3* corners = &triangles_.corner_positions[c];
    const double reach = std::max(
        {length(corners[1] - corners[0]), length(corners[2] - corners[1]), length(corners[0] - corners[2])});
    const Vec3& n = triangles_.face_normals[triangle];
    const Shape& shape = *scene_.primitives[triangles_.primitives[triangle]].shape;
    double best = kInfinity;
    Vec3 best_point = p;
    for (const Vec3& direction : {n, -n}) {
      SurfaceHit hit;
      if (shape.intersect(Ray{p, direction, 0.0, reach}, hit) && hit.t < best) {
        best = hit.t;
        best_point = hit.position;
      }
    }
    return best_point;
  }

  // The local model at a surface point (the ray tracer's own, shadows as raster.shadows).
  Color local_model(uint32_t triangle, const Vec3& position, const Vec3& object_position, const Vec2& uv,
                    const Vec3& normal, TraceContext& context) const {
    Intersection hit;
    hit.primitive = triangles_.primitives[triangle];
    hit.surface.position = on_surface(triangle, position);
    hit.surface.object_position = object_position;
    hit.surface.uv = uv;
    const Vec3& face_normal = triangles_.face_normals[triangle];
    const double n_length = length(normal);
    hit.surface.shading_normal = n_length > 0 && std::isfinite(n_length) ? normal / n_length : face_normal;
    // The interpolated normal stands for the true surface's normal everywhere the model asks
    // for the geometric one (which side a light is on, the shadow-ray offset, the spherical
    // mapping): the face normal would step the terminator along the facets. It keeps the
    // face's side.
    hit.surface.geometric_normal = face_forward(hit.surface.shading_normal, face_normal);
    const Material& material = scene_.materials[triangles_.materials[triangle]];
    const SurfaceProperties at = material.at(hit.surface);
    return local_illumination(scene_, hit, at, toward_viewer(position), settings_.shadows, context, -1);
  }

  // The varyings of corner k (0..2) of a triangle; `out` has varying_count() entries.
  void corner_varyings(uint32_t triangle, int k, double* out, TraceContext& context) const {
    const std::size_t corner = 3 * std::size_t(triangle) + k;
    const Vec3& p = triangles_.corner_positions[corner];
    const Vec3& q = triangles_.corner_object_positions[corner];
    const Vec2& uv = triangles_.corner_uvs[corner];
    const Vec3& n = triangles_.corner_normals[corner];
    if (settings_.shading == RasterShading::gouraud) {
      // 000 §3.2: the intensity at the vertex from the vertex normal.
      const Color I = local_model(triangle, p, q, uv, n, context);
      out[0] = I.r;
      out[1] = I.g;
      out[2] = I.b;
      return;
    }
    out[kPosition] = p.x, out[kPosition + 1] = p.y, out[kPosition + 2] = p.z;
    out[kObjectPosition] = q.x, out[kObjectPosition + 1] = q.y, out[kObjectPosition + 2] = q.z;
    out[kUv] = uv.x, out[kUv + 1] = uv.y;
    if (settings_.shading == RasterShading::phong) {
      out[kNormal] = n.x, out[kNormal + 1] = n.y, out[kNormal + 2] = n.z;
      return;
    }
    // 000 §3.4: N·L and the specular term of each light at the vertex.
    const Vec3 V = toward_viewer(p);
    const Vec3 N = face_forward(length_squared(n) > 0 ? n : triangles_.face_normals[triangle], V);
    const Material& material = scene_.materials[triangles_.materials[triangle]];
    SurfaceHit hit;
    hit.position = p;
    hit.object_position = q;
    hit.uv = uv;
    hit.geometric_normal = hit.shading_normal = N;
    const SurfaceProperties at = material.at(hit);
    double* light_out = out + kSurfaceVaryings;
    for (std::size_t e = 0; e < scene_.emitter_count(); ++e) {
      LightSample sample;
      Vec3 L;
      if (scene_.emitter(e).illuminate(p, sample))
        L = sample.direction;
      else
        L = -N;  // outside a spot cone: no light from it here
      const double n_dot_l = dot(N, L);
      Color specular;
      if (n_dot_l > 0 && at.ks > 0) {
        if (material.specular_model == SpecularModel::cook_torrance) {
          specular = at.ks * n_dot_l * cook_torrance(N, V, L, at.roughness, material.fresnel);
        } else {
          const double cosine = material.specular_model == SpecularModel::phong ? dot(reflect(L, N), V)
                                                                                : dot(N, normalize(L + V));
          if (cosine > 0) specular = Color(at.ks * std::pow(cosine, at.shininess));
        }
      }
      light_out[0] = n_dot_l;
      light_out[1] = specular.r, light_out[2] = specular.g, light_out[3] = specular.b;
      light_out += kPerLight;
    }
  }

  // The color of a pixel whose nearest surface is `triangle` with interpolated varyings.
  Color shade(uint32_t triangle, const double* v, const Color& flat_color, TraceContext& context) const {
    switch (settings_.shading) {
      case RasterShading::flat:
        return flat_color;
      case RasterShading::gouraud:
        return {v[0], v[1], v[2]};
      case RasterShading::phong:
        return local_model(triangle, {v[kPosition], v[kPosition + 1], v[kPosition + 2]},
                           {v[kObjectPosition], v[kObjectPosition + 1], v[kObjectPosition + 2]},
                           {v[kUv], v[kUv + 1]}, {v[kNormal], v[kNormal + 1], v[kNormal + 2]}, context);
      case RasterShading::dot_product:
        return dot_product(triangle, v, context);
    }
    return {};
  }

  // Flat shading (000 §3.1): the model once, at the centroid, with the face normal.
  Color flat(uint32_t triangle, TraceContext& context) const {
    const std::size_t c = 3 * std::size_t(triangle);
    const Vec3 p = (triangles_.corner_positions[c] + triangles_.corner_positions[c + 1] +
                    triangles_.corner_positions[c + 2]) /
                   3;
    const Vec3 q = (triangles_.corner_object_positions[c] + triangles_.corner_object_positions[c + 1] +
                    triangles_.corner_object_positions[c + 2]) /
                   3;
    const Vec2 uv{
        (triangles_.corner_uvs[c].x + triangles_.corner_uvs[c + 1].x + triangles_.corner_uvs[c + 2].x) / 3,
        (triangles_.corner_uvs[c].y + triangles_.corner_uvs[c + 1].y + triangles_.corner_uvs[c + 2].y) / 3};
    return local_model(triangle, p, q, uv, triangles_.face_normals[triangle], context);
  }

 private:
  Color dot_product(uint32_t triangle, const double* v, TraceContext& context) const {
    const Vec3 p = on_surface(triangle, {v[kPosition], v[kPosition + 1], v[kPosition + 2]});
    SurfaceHit hit;
    hit.position = p;
    hit.object_position = {v[kObjectPosition], v[kObjectPosition + 1], v[kObjectPosition + 2]};
    hit.uv = {v[kUv], v[kUv + 1]};
    hit.geometric_normal = hit.shading_normal =
        face_forward(triangles_.face_normals[triangle], toward_viewer(p));
    const Material& material = scene_.materials[triangles_.materials[triangle]];
    const SurfaceProperties at = material.at(hit);
    Color result = at.ka * scene_.ambient;
    const double offset = scene_.ray_offset(p);
    const double* light_in = v + kSurfaceVaryings;
    for (std::size_t e = 0; e < scene_.emitter_count(); ++e) {
      const Light& light = scene_.emitter(e);
      const double n_dot_l = light_in[0];
      const Color specular{light_in[1], light_in[2], light_in[3]};
      light_in += kPerLight;
      LightSample sample;
      if (n_dot_l <= 0 || !light.illuminate(p, sample)) continue;
      const Color s =
          settings_.shadows ? visible_fraction(light, e, p, hit.geometric_normal, offset, context) : Color(1);
      result += sample.intensity * s * (at.kd * n_dot_l + specular);
    }
    return result;
  }

  // The share of a light's intensity that reaches p past the occluders: one shadow ray toward a
  // point light, and for an area light or an emissive surface its samples, each jittered within
  // its cell per shading point as the ray tracer does (StratumJitter), weighted by what each
  // carries — so its shadows have penumbrae rather than the hard edge of its centre.
  Color visible_fraction(const Light& light, std::size_t e, const Vec3& p, const Vec3& normal, double offset,
                         TraceContext& context) const {
    const Vec3 origin = p + normal * offset;
    if (light.sample_count() == 1) {  // the point the dot product was taken toward
      LightSample sample;
      if (!light.illuminate(p, sample)) return {};
      return shadow_transmittance(scene_, origin, sample.direction, shadow_reach(sample, offset), context,
                                  -1);
    }
    const StratumJitter jitter{true, context.seed};  // the render's seed
    Color reached, total;
    for_each_light_sample(light, e, p, offset, jitter, [&](const LightSample& sample, double reach) {
      total += sample.intensity;
      if (dot(normal, sample.direction) <= 0) return;  // behind the face: this part of the light is not seen
      reached +=
          sample.intensity * shadow_transmittance(scene_, origin, sample.direction, reach, context, -1);
    });
    Color fraction;
    for (int c = 0; c < 3; ++c) fraction[c] = total[c] > 0 ? reached[c] / total[c] : 0;
    return fraction;
  }

  const Scene& scene_;
  const TessellatedScene& triangles_;
  RasterSettings settings_;
  bool perspective_;
  Vec3 eye_, view_direction_;
};

// Per-tile buffers: the winning triangle and its varyings per pixel.
struct TileBuffers {
  std::vector<uint32_t> triangle;
  std::vector<double> varyings;
};

}  // namespace

namespace {

// The scene's tessellation for the camera's view on the sample grid: curved shapes by their size on
// screen, planes cut by a box around the scene, the eye and the planes' points nearest the eye, a
// hundred times its size (a floor reaches a horizon far beyond the scene).
TessellationRequest tessellation_for_view(const Scene& scene, const SampleGrid& grid,
                                          const RasterSettings& settings) {
  const Camera& camera = *scene.camera;
  const Bounds3 clip = raster_clip_box(scene, camera.eye_position(), 100);
  // Depth range: everything inside the clip box; near small enough for the closest surface.
  const double far = 2 * length(clip.diagonal());
  const double near = far * 1e-8;
  Eigen::Matrix4d clip_from_world = camera.view_projection(near, far);
  // The grid's rasterizer has its pixel centres on the sample points.
  clip_from_world.row(0) *= grid.ndc_scale(camera.width());
  clip_from_world.row(1) *= grid.ndc_scale(camera.height());
  TessellationRequest tessellation;
  tessellation.max_segments = settings.segments;
  tessellation.crease_angle_degrees = settings.crease_angle;
  tessellation.clip = clip;
  tessellation.has_view = true;
  tessellation.clip_from_world = clip_from_world;
  tessellation.image_width = camera.width();
  tessellation.eye = camera.eye_position();
  return tessellation;
}

}  // namespace

// The image, the samples of the grid (colour and depth) and the view's triangles with
// their per-corner clip positions and varyings.
std::vector<MemoryPart> RasterMethod::memory_needed(const Scene& scene, const RenderRequest& request) const {
  std::vector<MemoryPart> parts = Method::memory_needed(scene, request);
  const PixelRect& region = request.region;
  const AntialiasingSettings& antialiasing = request.antialiasing_for(scene);
  std::optional<SampleGrid> grid = sample_grid(antialiasing);
  if (drawn_in_passes(antialiasing)) {
    // The image itself, drawn once per pass.
    grid = SampleGrid{};
    const SamplingRegion sampling{region.x0, region.y0, scene.camera->width(), scene.camera->height()};
    const PixelBox pixels = pixels_drawn_in_passes(antialiasing, sampling, region.width(), region.height());
    parts.push_back(
        image_memory_part("the passes' samples and sums", accumulation_bytes(antialiasing, pixels)));
  }
  if (!grid) return parts;  // refused as it is rendered
  if (!drawn_in_passes(antialiasing)) {
    const uint64_t samples = static_cast<uint64_t>(grid->end(region.width())) * grid->end(region.height());
    parts.push_back({"the samples", samples * (sizeof(Color) + sizeof(double)), "aa.n", "lower it"});
  }
  const std::size_t triangles =
      tessellated_triangle_count(scene, tessellation_for_view(scene, *grid, settings_));
  // The tessellation three times at its peak (its arrays grow by doubling), then clip positions and
  // varyings per corner and a flat colour.
  constexpr std::size_t kRasterTriangleBytes =
      3 * kTessellatedTriangleBytes + 3 * sizeof(Eigen::Vector4d) + 3 * 4 * sizeof(double) + sizeof(Color);
  parts.push_back({fmt::format("the {} triangles of the view", triangles),
                   static_cast<uint64_t>(triangles) * kRasterTriangleBytes, "raster.segments",
                   "lower it (curved shapes' divisions of a full turn)"});
  return parts;
}

void RasterMethod::refuse_scene(const Scene& scene) const {
  refuse_dot_product_scene(settings_, scene);
}

std::optional<AntialiasingRefusal> RasterMethod::antialiasing_refusal(
    const Scene& scene, const AntialiasingSettings& antialiasing) const {
  return sample_grid_refusal(antialiasing, scene);
}

namespace {

// The side of the tiles a view is drawn in: the grid's own tiles, whatever the region.
constexpr int kRasterTile = 32;

// Tiles of the grid samples, aligned on the grid's own tiles of kRasterTile (a scanline started
// inside a span agrees with a whole-image draw only to rounding, so every region starts its spans
// where the whole image does), each with the triangles whose screen bounds reach it (a triangle
// with a vertex behind the eye plane may reach anywhere once clipped: every tile gets it). A pass
// moves the image by less than a pixel: drawn in passes (margin 1), a triangle is binned by its
// bounds grown by a pixel, and kept unless it lies that far outside the frustum's sides.
std::vector<std::vector<uint32_t>> bin_triangles(const std::vector<Eigen::Vector4d>& clip_positions,
                                                 const PixelBox& samples_box, int margin, int grid_width,
                                                 int grid_height) {
  const int tile = kRasterTile;
  const std::size_t triangle_count = clip_positions.size() / 3;
  const double side_x = 1.0 + 2.0 * margin / grid_width, side_y = 1.0 + 2.0 * margin / grid_height;
  const int first_tx = samples_box.x0 / tile, first_ty = samples_box.y0 / tile;
  const int tiles_x = (samples_box.x1 - 1) / tile - first_tx + 1;
  const int tiles_y = (samples_box.y1 - 1) / tile - first_ty + 1;
  std::vector<std::vector<uint32_t>> bins(std::size_t(tiles_x) * tiles_y);
  for (std::size_t t = 0; t < triangle_count; ++t) {
    // Outside one of the six clip planes with all three corners: in no tile.
    int outside_all = 0x3F;
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector4d& c = clip_positions[3 * t + k];
      const int outside = (c.x() < -side_x * c.w()) | (c.x() > side_x * c.w()) << 1 |
                          (c.y() < -side_y * c.w()) << 2 | (c.y() > side_y * c.w()) << 3 |
                          (c.z() < -c.w()) << 4 | (c.z() > c.w()) << 5;
      outside_all &= outside;
    }
    if (outside_all != 0) continue;
    int tx0 = 0, ty0 = 0, tx1 = tiles_x - 1, ty1 = tiles_y - 1;
    auto [lower_x, upper_x, lower_y, upper_y, in_front] = screen_bounds(
        clip_positions[3 * t], clip_positions[3 * t + 1], clip_positions[3 * t + 2], grid_width, grid_height);
    if (in_front) {
      lower_x -= margin, upper_x += margin, lower_y -= margin, upper_y += margin;
      if (!(upper_x >= samples_box.x0 && lower_x <= samples_box.x1 && upper_y >= samples_box.y0 &&
            lower_y <= samples_box.y1))
        continue;
      const auto tile_of = [&](double v, int first, int count) {
        return std::clamp(static_cast<int>(std::floor(std::clamp(v, -1e9, 1e9) / tile)) - first, 0,
                          count - 1);
      };
      tx0 = tile_of(lower_x, first_tx, tiles_x), tx1 = tile_of(upper_x, first_tx, tiles_x);
      ty0 = tile_of(lower_y, first_ty, tiles_y), ty1 = tile_of(upper_y, first_ty, tiles_y);
    }
    for (int ty = ty0; ty <= ty1; ++ty)
      for (int tx = tx0; tx <= tx1; ++tx)
        bins[std::size_t(ty) * tiles_x + tx].push_back(static_cast<uint32_t>(t));
  }
  return bins;
}

// A view's triangles, transformed once and binned by tile (bin_triangles), and what drawing its
// tiles needs.
struct ViewTiles {
  const Scene& scene;
  const SampleGrid& grid;
  const RasterShader& shader;
  const std::vector<Eigen::Vector4d>& clip_positions;
  const std::vector<double>& corner_varyings;  // varying_count per corner, `stride` apart
  const std::vector<Color>& flat_colors;       // per triangle, for flat shading
  const std::vector<std::vector<uint32_t>>& bins;
  PixelBox samples_box;
  int grid_width, grid_height, varying_count;
  std::size_t stride;
  int first_tx, first_ty, tiles_x;

  // Draws tile `index` into out (samples_box-sized, row by row): on the grid (no offset), or one
  // pass's samples of the pixels `wanted` (samples_box-sized); false for a tile with none of them.
  bool draw_tile(int index, const PassOffset* offset, const std::vector<uint8_t>* wanted, Color* out,
                 TraceContext& context, RasterStatistics& statistics) const {
    const int tile = kRasterTile;
    const Camera& camera = *scene.camera;
    // The tile's spans start at its aligned left edge, where the whole image's do, also when the
    // region's samples begin inside it (rows are evaluated directly: any first row will do).
    const int span_x0 = (first_tx + index % tiles_x) * tile;
    const int x0 = std::max(samples_box.x0, span_x0);
    const int y0 = std::max(samples_box.y0, (first_ty + index / tiles_x) * tile);
    const int x1 = std::min((first_tx + index % tiles_x + 1) * tile, samples_box.x1);
    const int y1 = std::min((first_ty + index / tiles_x + 1) * tile, samples_box.y1);
    const auto out_index = [&](int x, int y) {
      return std::size_t(y - samples_box.y0) * samples_box.width() + (x - samples_box.x0);
    };
    const auto is_wanted = [&](int x, int y) { return !wanted || (*wanted)[out_index(x, y)] != 0; };
    bool any_wanted = false;
    for (int y = y0; y < y1 && !any_wanted; ++y)
      for (int x = x0; x < x1 && !any_wanted; ++x) any_wanted = is_wanted(x, y);
    if (!any_wanted) return false;
    const double shift_x = offset ? offset->ndc_shift_x(grid_width) : 0.0;
    const double shift_y = offset ? offset->ndc_shift_y(grid_height) : 0.0;
    const int w = x1 - span_x0;
    Rasterizer rasterizer(grid_width, grid_height, span_x0, y0, x1, y1);  // cleared
    TileBuffers buffers;
    buffers.triangle.assign(std::size_t(w) * (y1 - y0), UINT32_MAX);
    buffers.varyings.assign(buffers.triangle.size() * stride, 0.0);
    std::array<RasterVertex, 3> corners;
    for (const uint32_t id : bins[std::size_t(index)]) {
      const std::size_t t = id;
      for (int k = 0; k < 3; ++k) {
        corners[k].clip = clip_positions[3 * t + k];
        if (offset) {
          corners[k].clip.x() += corners[k].clip.w() * shift_x;
          corners[k].clip.y() += corners[k].clip.w() * shift_y;
        }
        if (varying_count > 0)
          std::copy_n(corner_varyings.data() + (3 * t + k) * stride, varying_count,
                      corners[k].varyings.begin());
      }
      rasterizer.draw_triangle(
          corners[0], corners[1], corners[2], varying_count, [&](const Fragment& fragment) {
            const std::size_t pixel = std::size_t(fragment.y - y0) * w + (fragment.x - span_x0);
            buffers.triangle[pixel] = id;
            std::copy_n(fragment.varyings, varying_count, buffers.varyings.begin() + pixel * stride);
            return true;
          });
    }
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) {
        if (!is_wanted(x, y)) continue;
        const std::size_t pixel = std::size_t(y - y0) * w + (x - span_x0);
        const uint32_t t = buffers.triangle[pixel];
        const double image_x = offset ? x + offset->dx : grid.position(x);
        const double image_y = offset ? y + offset->dy : grid.position(y);
        out[out_index(x, y)] = t == UINT32_MAX
                                   ? scene.background_along(camera.generate_ray(image_x, image_y).direction)
                                   : shader.shade(t, buffers.varyings.data() + pixel * stride,
                                                  flat_colors.empty() ? Color() : flat_colors[t], context);
      }
    const RasterStatistics& own = rasterizer.statistics();
    statistics.fragments += own.fragments;
    statistics.written += own.written;
    return true;
  }
};

// The view of a render, made once for any region of its image: the scene tessellated for the
// camera, each triangle's corners in clip space with their varyings (Gouraud's vertex intensities)
// and flat colours. draw(area) then draws a region of the image — the whole image on one process,
// a tile at a time across ranks — with what it drew added up for the statistics.
class RasterView {
 public:
  RasterView(const Scene& scene, const RasterSettings& settings, const AntialiasingSettings& antialiasing,
             uint64_t seed)
      : scene_(scene),
        antialiasing_(antialiasing),
        seed_(seed),
        in_passes_(drawn_in_passes(antialiasing)),
        grid_(in_passes_ ? SampleGrid{} : *sample_grid(antialiasing)),
        grid_width_(static_cast<int>(grid_.end(scene.camera->width()))),
        grid_height_(static_cast<int>(grid_.end(scene.camera->height()))),
        tessellation_(tessellation_for_view(scene, grid_, settings)),
        triangles_(tessellate_scene(scene, tessellation_)),
        tessellation_seconds_(tessellation_time_.seconds()),
        shader_(scene, triangles_, settings),
        varying_count_(shader_.varying_count()),
        stride_(static_cast<std::size_t>(std::max(varying_count_, 1))),
        contexts_([seed] {
          TraceContext context;
          context.seed = seed;
          return context;
        }) {
    // Per-vertex work once: clip coordinates and varyings, packed (varying_count per corner).
    const std::size_t count = triangles_.triangle_count();
    clip_positions_.resize(3 * count);
    corner_varyings_.resize(varying_count_ > 0 ? 3 * count * stride_ : 0);
    flat_colors_.resize(settings.shading == RasterShading::flat ? count : 0);
    tbb::parallel_for(std::size_t(0), count, [&](std::size_t t) {
      TraceContext& context = contexts_.local();
      for (int k = 0; k < 3; ++k) {
        const Vec3& p = triangles_.corner_positions[3 * t + k];
        clip_positions_[3 * t + k] = tessellation_.clip_from_world * Eigen::Vector4d(p.x, p.y, p.z, 1);
        if (varying_count_ > 0)
          shader_.corner_varyings(static_cast<uint32_t>(t), k, &corner_varyings_[(3 * t + k) * stride_],
                                  context);
      }
      if (!flat_colors_.empty()) flat_colors_[t] = shader_.flat(static_cast<uint32_t>(t), context);
    });
  }

  // Draws `area` of the image into target (area-sized): the grid's samples of its pixels (and the
  // ring its filter reaches) reconstructed with the scene's filter, or the jittered passes
  // splatted (camera/accumulation_buffer.h). Spans start where the whole image's do, so any
  // region gives the whole image's pixels.
  void draw(const PixelRect& area, Film& target, bool quiet) {
    const Camera& camera = *scene_.camera;
    const SamplingRegion sampling{area.x0, area.y0, camera.width(), camera.height()};
    const PixelBox pixels = in_passes_
                                ? pixels_drawn_in_passes(antialiasing_, sampling, area.width(), area.height())
                                : sampled_pixels(antialiasing_, sampling, area.width(), area.height());
    const PixelBox samples_box{
        static_cast<int>(grid_.first(pixels.x0)), static_cast<int>(grid_.first(pixels.y0)),
        static_cast<int>(grid_.end(pixels.x1)), static_cast<int>(grid_.end(pixels.y1))};
    const int tile = kRasterTile;
    const int first_tx = samples_box.x0 / tile, first_ty = samples_box.y0 / tile;
    const int tiles_x = (samples_box.x1 - 1) / tile - first_tx + 1;
    const int tiles_y = (samples_box.y1 - 1) / tile - first_ty + 1;
    const std::vector<std::vector<uint32_t>> bins =
        bin_triangles(clip_positions_, samples_box, in_passes_ ? 1 : 0, grid_width_, grid_height_);
    const ViewTiles view{scene_,         grid_,   shader_,     clip_positions_, corner_varyings_,
                         flat_colors_,   bins,    samples_box, grid_width_,     grid_height_,
                         varying_count_, stride_, first_tx,    first_ty,        tiles_x};
    const auto draw_tile = [&](int index, const PassOffset* offset, const std::vector<uint8_t>* wanted,
                               Color* out) {
      if (cancel_requested()) return;  // Ctrl-C: the tiles not begun stay black
      if (view.draw_tile(index, offset, wanted, out, contexts_.local(), tile_statistics_.local()))
        tiles_done_.fetch_add(1, std::memory_order_relaxed);
    };
    if (in_passes_) {
      ProgressReporter progress("raster", static_cast<uint64_t>(PassSchedule(antialiasing_, seed_).passes()),
                                "passes", quiet);
      const PassDrawing draw_pass = [&](int, const PassOffset& offset, const PixelBox& box,
                                        const std::vector<uint8_t>& wanted, std::vector<Color>& values) {
        if (box.x0 != samples_box.x0 || box.y0 != samples_box.y0 || box.x1 != samples_box.x1 ||
            box.y1 != samples_box.y1)
          throw std::logic_error("raster: a pass asked for other pixels than the view was binned for");
        tbb::parallel_for(0, tiles_x * tiles_y,
                          [&](int index) { draw_tile(index, &offset, &wanted, values.data()); });
        progress.advance();
      };
      const PassesResult drawn = accumulate_passes(antialiasing_, seed_, sampling, draw_pass, target);
      progress.finish();
      passes_.passes = std::max(passes_.passes, drawn.passes);
      passes_.most_passes = drawn.most_passes;
      passes_.samples += drawn.samples;
      passes_.refined_pixels += drawn.refined_pixels;
    } else {
      Film samples(samples_box.width(), samples_box.height());
      ProgressReporter progress("raster", static_cast<uint64_t>(tiles_x) * tiles_y, "tiles", quiet);
      tbb::parallel_for(0, tiles_x * tiles_y, [&](int index) {
        draw_tile(index, nullptr, nullptr,
                  samples.width() > 0 && samples.height() > 0 ? &samples.at(0, 0) : nullptr);
        progress.advance();
      });
      progress.finish();
      // The pixels from the grid's samples, reconstructed with the scene's filter.
      const RadianceFunction sample_at = [&](double x, double y) {
        const auto i = std::clamp<int64_t>(grid_.index(x) - samples_box.x0, 0, samples.width() - 1);
        const auto j = std::clamp<int64_t>(grid_.index(y) - samples_box.y0, 0, samples.height() - 1);
        return samples.at(static_cast<int>(i), static_cast<int>(j));
      };
      sample_image(antialiasing_, seed_, sampling, scene_.render.tile_size, sample_at, target);
    }
    tiles_total_ += static_cast<uint64_t>(tiles_x) * tiles_y;
  }

  // What the draws so far did: "N of M tiles" or "N of M passes".
  std::string completed() const {
    return in_passes_ ? fmt::format("{} of {} passes", passes_.passes, passes_.most_passes)
                      : fmt::format("{} of {} tiles", tiles_done_.load(), tiles_total_);
  }
  // Counts of this process, summed over the ranks when a cluster is given (a collective).
  RayCounts shadow_rays(Cluster* cluster) const {
    RayCounts total;
    for (const TraceContext& context : contexts_) total += context.counts;
    if (cluster) sum_across_ranks(*cluster, total);
    return total;
  }
  nlohmann::json facts(const RasterSettings& settings, Cluster* cluster) const {
    std::vector<uint64_t> counts{0, 0, passes_.samples, passes_.refined_pixels};
    for (const RasterStatistics& s : tile_statistics_) {
      counts[0] += s.fragments;
      counts[1] += s.written;
    }
    if (cluster) cluster->sum(counts);
    // Sub-phases of "render", kept out of the phase list so the total is not counted twice.
    nlohmann::json facts = {{"shading", kRasterShadingNames.name(settings.shading)},
                            {"segments", settings.segments},
                            {"tessellate_seconds", tessellation_seconds_},
                            {"rasterize_and_shade_seconds", raster_time_.seconds()},
                            {"triangles", triangles_.triangle_count()},
                            {"fragments", counts[0]},
                            {"depth_writes", counts[1]}};
    if (in_passes_)
      facts["accumulation"] = {
          {"passes", passes_.passes}, {"refined_pixels", counts[3]}, {"samples", counts[2]}};
    return facts;
  }

 private:
  const Scene& scene_;
  const AntialiasingSettings& antialiasing_;
  uint64_t seed_;
  bool in_passes_;
  // The scene is drawn at the points of the aa mode's sample grid (camera/sample_grid.h); jittered
  // samples lie off every grid: then the image is drawn at its own size once per pass, its
  // projection moved by the pass's sub-pixel offset.
  SampleGrid grid_;
  int grid_width_, grid_height_;
  Stopwatch tessellation_time_;
  TessellationRequest tessellation_;
  TessellatedScene triangles_;
  double tessellation_seconds_;
  Stopwatch raster_time_;  // from the tessellation's end: the per-vertex work and the draws
  RasterShader shader_;
  int varying_count_;
  std::size_t stride_;
  std::vector<Eigen::Vector4d> clip_positions_;
  std::vector<double> corner_varyings_;
  std::vector<Color> flat_colors_;
  tbb::enumerable_thread_specific<TraceContext> contexts_;
  tbb::enumerable_thread_specific<RasterStatistics> tile_statistics_;
  std::atomic<uint64_t> tiles_done_{0};
  uint64_t tiles_total_ = 0;
  PassesResult passes_;
};

}  // namespace

RenderResult RasterMethod::render(const Scene& scene, const RenderRequest& request) const {
  // The render's aa settings and seed, which may not be the scene's.
  const AntialiasingSettings& antialiasing = request.antialiasing_for(scene);
  refuse_unsupported_antialiasing(*this, scene, antialiasing);
  RenderResult output(request.region);
  RunStatistics& statistics = output.statistics;
  Cluster* cluster = several_ranks(request);
  RasterView view(scene, settings_, antialiasing, request.seed_for(scene));
  // Across ranks every rank makes the view and draws the tiles handed to it.
  draw_across_ranks(
      cluster, request.region,
      [&](const PixelRect& area, Film& target) { view.draw(area, target, request.quiet || cluster); },
      output.film, statistics);
  if (cancel_requested()) {
    statistics.extra["interrupted"] = true;
    statistics.extra["completed"] = view.completed();
  }
  statistics.rays += view.shadow_rays(cluster);
  statistics.pixels += static_cast<uint64_t>(request.region.width()) * request.region.height();
  statistics.extra["raster"] = view.facts(settings_, cluster);
  return output;
}

}  // namespace candela
