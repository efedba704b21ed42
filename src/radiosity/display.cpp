#include "radiosity/display.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstddef>
#include <optional>
#include <stdexcept>

#include "camera/antialiasing.h"
#include "math/bounds.h"
#include "scene/scene.h"

namespace candela {
namespace {

// Barycentric coordinates (weights of corners 0, 1, 2) of a point projected on a triangle's
// plane, clamped to the triangle.
std::array<double, 3> barycentric(const std::array<Vec3, 3>& corners, const Vec3& point) {
  const Vec3 e1 = corners[1] - corners[0], e2 = corners[2] - corners[0], d = point - corners[0];
  const double d11 = dot(e1, e1), d12 = dot(e1, e2), d22 = dot(e2, e2), d1 = dot(d, e1), d2 = dot(d, e2);
  const double denominator = d11 * d22 - d12 * d12;
  double v = denominator > 0 ? (d22 * d1 - d12 * d2) / denominator : 0;
  double w = denominator > 0 ? (d11 * d2 - d12 * d1) / denominator : 0;
  v = std::clamp(v, 0.0, 1.0);
  w = std::clamp(w, 0.0, 1.0 - v);
  return {1 - v - w, v, w};
}

// The element mesh (000 Figure 65): each element flat, its edges drawn dark about a pixel wide —
// where the hit lies closer to an edge than pixel_footprint (the width a pixel covers there).
Color element_outline(const RadiositySolveResult& solution, uint32_t element, const Intersection& hit,
                      double pixel_footprint) {
  const RadiositySurface& surface = solution.mesh.elements[element];
  const auto weights = barycentric(surface.corners, hit.surface.position);
  for (int k = 0; k < 3; ++k) {
    // Weight k is the distance to the opposite edge over the triangle's height there, 2A/|edge|.
    const double edge = length(surface.corners[(k + 2) % 3] - surface.corners[(k + 1) % 3]);
    if (edge > 0 && weights[static_cast<std::size_t>(k)] * 2 * surface.area / edge < 0.6 * pixel_footprint)
      return solution.element_radiosity[element] * 0.15;
  }
  return solution.element_radiosity[element];
}

}  // namespace

// 000 §6.5 and SPEC §10 "a ray-traced view that looks the value up at each hit": a ray through
// each pixel centre; at its hit, the element under the hit point, and the vertex radiosities of
// that element interpolated at the point's barycentric coordinates (the same field the Gouraud
// display shows, without its screen-space interpolation).
Color ray_traced_radiosity(const RadiositySolveResult& solution, const VertexRadiosity& vertices,
                           uint32_t element, const Intersection& hit) {
  const auto weights = barycentric(solution.mesh.elements[element].corners, hit.surface.position);
  const auto& ids = vertices.element_vertices[element];
  return vertices.radiosity[ids[0]] * weights[0] + vertices.radiosity[ids[1]] * weights[1] +
         vertices.radiosity[ids[2]] * weights[2];
}

SolutionDisplay::SolutionDisplay(const Scene& scene, const RadiositySolveResult& solution,
                                 RadiosityDisplay display, const AntialiasingSettings& antialiasing,
                                 uint64_t seed)
    : scene_(scene), solution_(solution), display_(display), antialiasing_(antialiasing), seed_(seed) {
  if (display != RadiosityDisplay::gouraud && display != RadiosityDisplay::ray_traced) return;
  vertices_ =
      compute_vertex_radiosity(solution.mesh.elements, solution.element_radiosity, solution.element_hidden);
  if (display != RadiosityDisplay::gouraud) return;
  // Jittered samples lie off every grid: the image's own pixels, drawn once per pass.
  in_passes_ = drawn_in_passes(antialiasing_);
  grid_ = in_passes_ ? SampleGrid{} : *sample_grid(antialiasing_);
  // 000 §6.5: the elements drawn as triangles through the scanline rasterizer with their vertex
  // radiosities as colors, interpolated perspective-correctly (Gouraud). Projected once, here;
  // draw fills any region from them.
  const Camera& camera = *scene.camera;
  const std::vector<RadiositySurface>& elements = solution.mesh.elements;
  // Depth range: a box around the elements and the eye; near small enough for the closest element.
  Bounds3 bounds;
  bounds.extend(camera.eye_position());
  for (const RadiositySurface& element : elements)
    for (const Vec3& corner : element.corners) bounds.extend(corner);
  const double far = 2 * length(bounds.diagonal()) + 1;
  Eigen::Matrix4d clip_from_world = camera.view_projection(far * 1e-8, far);
  // The grid's rasterizer has its pixel centres on the sample points.
  clip_from_world.row(0) *= grid_.ndc_scale(camera.width());
  clip_from_world.row(1) *= grid_.ndc_scale(camera.height());
  const int grid_width = static_cast<int>(grid_.end(camera.width()));
  const int grid_height = static_cast<int>(grid_.end(camera.height()));
  triangles_.resize(elements.size());
  bounds_on_screen_.resize(elements.size());
  for (std::size_t q = 0; q < elements.size(); ++q) {
    for (std::size_t k = 0; k < 3; ++k) {
      const Vec3& p = elements[q].corners[k];
      RasterVertex& vertex = triangles_[q][k];
      vertex.clip = clip_from_world * Eigen::Vector4d(p.x, p.y, p.z, 1);
      const Color& b = vertices_.radiosity[vertices_.element_vertices[q][k]];
      vertex.varyings[0] = b.r, vertex.varyings[1] = b.g, vertex.varyings[2] = b.b;
    }
    bounds_on_screen_[q] = screen_bounds(triangles_[q][0].clip, triangles_[q][1].clip, triangles_[q][2].clip,
                                         grid_width, grid_height);
    // A two-sided surface's element seen from behind: its twin is drawn there. Its
    // winding on screen says which side faces the eye (counter-clockwise, y up: the front).
    if (elements[q].two_sided && bounds_on_screen_[q].in_front) {
      const auto ndc = [&](int k) {
        const Eigen::Vector4d& c = triangles_[q][k].clip;
        return Vec2{c.x() / c.w(), c.y() / c.w()};
      };
      const Vec2 a = ndc(0), b = ndc(1), c = ndc(2);
      if ((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x) < 0)
        bounds_on_screen_[q] = {1, -1, 1, -1, false};  // an empty box: never drawn
    }
  }
}

uint64_t SolutionDisplay::draw(int x0, int y0, Film& film) const {
  const Camera& camera = *scene_.camera;
  const AntialiasingSettings& aa = antialiasing_;
  const SamplingRegion at{x0, y0, camera.width(), camera.height()};
  if (display_ != RadiosityDisplay::gouraud) {
    const RadianceFunction radiance = [&](double x, double y) { return ray_cast(x, y); };
    return sample_image(aa, seed_, at, scene_.render.tile_size, radiance, film).traced;
  }
  if (in_passes_) {
    // Every sample of a pass is drawn (the rasterizer's interpolation is all its cost).
    const PassDrawing draw_pass = [&](int, const PassOffset& offset, const PixelBox& box,
                                      const std::vector<uint8_t>&, std::vector<Color>& values) {
      Film samples(box.width(), box.height());
      draw_rasterized(box.x0, box.y0, &offset, samples);
      for (int y = 0; y < box.height(); ++y)
        for (int x = 0; x < box.width(); ++x) values[std::size_t(y) * box.width() + x] = samples.at(x, y);
    };
    return accumulate_passes(aa, seed_, at, draw_pass, film).samples;
  }
  // The grid samples of every pixel sample_image asks about, rasterized first.
  const PixelBox pixels = sampled_pixels(aa, at, film.width(), film.height());
  const int64_t gx0 = grid_.first(pixels.x0), gy0 = grid_.first(pixels.y0);
  Film samples(static_cast<int>(grid_.end(pixels.x1) - gx0), static_cast<int>(grid_.end(pixels.y1) - gy0));
  draw_rasterized(gx0, gy0, nullptr, samples);
  const RadianceFunction radiance = [&](double x, double y) {
    const auto i = std::clamp<int64_t>(grid_.index(x) - gx0, 0, samples.width() - 1);
    const auto j = std::clamp<int64_t>(grid_.index(y) - gy0, 0, samples.height() - 1);
    return samples.at(static_cast<int>(i), static_cast<int>(j));
  };
  return sample_image(aa, seed_, at, scene_.render.tile_size, radiance, film).traced;
}

// Tiles of 32 × 32 grid samples, each drawn by one thread from the same inputs with its own depth
// buffer, so the image does not depend on the thread count; samples no element covers show the
// background.
void SolutionDisplay::draw_rasterized(int64_t gx0, int64_t gy0, const PassOffset* offset,
                                      Film& samples) const {
  const Camera& camera = *scene_.camera;
  const int grid_width = static_cast<int>(grid_.end(camera.width()));
  const int grid_height = static_cast<int>(grid_.end(camera.height()));
  const int x0 = static_cast<int>(gx0), y0 = static_cast<int>(gy0);
  const int region_x1 = x0 + samples.width(), region_y1 = y0 + samples.height();
  // Tiles aligned on the grid's own 32-sample tiles, whatever the region: a scanline started
  // inside a span agrees with a whole-image draw only to rounding, so every region starts its
  // spans where the whole image does.
  const int tile = 32;
  // A pass moves the image by less than a pixel: an element is drawn in the tiles its bounds
  // reach grown by a pixel.
  const int margin = offset ? 1 : 0;
  const int first_x = x0 / tile, first_y = y0 / tile;
  const int tiles_x = (region_x1 - 1) / tile - first_x + 1, tiles_y = (region_y1 - 1) / tile - first_y + 1;
  tbb::parallel_for(0, tiles_x * tiles_y, [&](int index) {
    // The spans start at the tile's aligned left edge also when the region begins inside it.
    const int span_x0 = (first_x + index % tiles_x) * tile;
    const int tile_x0 = std::max(x0, span_x0);
    const int tile_y0 = std::max(y0, (first_y + index / tiles_x) * tile);
    const int tile_x1 = std::min((first_x + index % tiles_x + 1) * tile, region_x1);
    const int tile_y1 = std::min((first_y + index / tiles_x + 1) * tile, region_y1);
    const int w = tile_x1 - span_x0;
    Rasterizer rasterizer(grid_width, grid_height, span_x0, tile_y0, tile_x1, tile_y1);  // cleared
    std::vector<Color> colors(std::size_t(w) * (tile_y1 - tile_y0));
    std::vector<bool> covered(colors.size(), false);
    for (std::size_t q = 0; q < triangles_.size(); ++q) {
      const ScreenBounds& box = bounds_on_screen_[q];
      if (box.upper_x < box.lower_x) continue;  // never drawn (a two-sided element's back)
      if (box.upper_x + margin < tile_x0 || box.lower_x - margin > tile_x1 ||
          box.upper_y + margin < tile_y0 || box.lower_y - margin > tile_y1)
        continue;  // misses the tile
      const auto draw = [&](const RasterVertex& a, const RasterVertex& b, const RasterVertex& c) {
        rasterizer.draw_triangle(a, b, c, 3, [&](const Fragment& fragment) {
          const std::size_t pixel = std::size_t(fragment.y - tile_y0) * w + (fragment.x - span_x0);
          colors[pixel] = {fragment.varyings[0], fragment.varyings[1], fragment.varyings[2]};
          covered[pixel] = true;
          return true;
        });
      };
      if (!offset) {
        draw(triangles_[q][0], triangles_[q][1], triangles_[q][2]);
        continue;
      }
      // The pass's projection: the corners moved in clip space (their colours, three varyings, kept).
      std::array<RasterVertex, 3> moved;
      for (std::size_t k = 0; k < 3; ++k) {
        const RasterVertex& corner = triangles_[q][k];
        moved[k].clip = corner.clip;
        moved[k].clip.x() += corner.clip.w() * offset->ndc_shift_x(grid_width);
        moved[k].clip.y() += corner.clip.w() * offset->ndc_shift_y(grid_height);
        std::copy_n(corner.varyings.begin(), 3, moved[k].varyings.begin());
      }
      draw(moved[0], moved[1], moved[2]);
    }
    for (int y = tile_y0; y < tile_y1; ++y)
      for (int x = tile_x0; x < tile_x1; ++x) {
        const std::size_t pixel = std::size_t(y - tile_y0) * w + (x - span_x0);
        const double image_x = offset ? x + offset->dx : grid_.position(x);
        const double image_y = offset ? y + offset->dy : grid_.position(y);
        samples.at(x - x0, y - y0) =
            covered[pixel] ? colors[pixel]
                           : scene_.background_along(camera.generate_ray(image_x, image_y).direction);
      }
  });
}

// By ray casting: the radiosity (view independent: B itself) where the ray hits.
Color SolutionDisplay::ray_cast(double x, double y) const {
  const Camera& camera = *scene_.camera;
  const Ray ray = camera.generate_ray(x, y);
  Intersection hit;
  const uint32_t element =
      scene_.intersect(ray, hit)
          ? solution_.mesh.element_at(hit.primitive, hit.surface.position, -ray.direction)
          : UINT32_MAX;
  if (element == UINT32_MAX)
    return scene_.background_along(ray.direction);  // a miss, or off the mesh (as the Gouraud display)
  if (display_ == RadiosityDisplay::ray_traced)
    return ray_traced_radiosity(solution_, vertices_, element, hit);
  if (display_ == RadiosityDisplay::elements) {
    // The outline about a pixel wide: the width one pixel covers at the hit.
    const Vec3 next = camera.generate_ray(x + 1, y).direction;
    return element_outline(
        solution_, element, hit,
        length(hit.surface.position - ray.origin) * length(normalize(next) - normalize(ray.direction)));
  }
  return solution_.element_radiosity[element];
}

}  // namespace candela
