// A radiosity solution drawn for the scene's camera (000 §6.5, SPEC §10 "Display"; setting
// radiosity.display), its pixels sampled and reconstructed by sample_image with the scene's aa
// settings (SPEC §17):
//   flat        a ray through each sample point; its hit → the element of the hit primitive
//               nearest the hit point → that element's radiosity B (the exitance, view
//               independent), shown directly as the seed's radiosity images are.
//   gouraud     the vertex radiosities of radiosity/vertex_radiosity.h; the elements drawn as
//               triangles by the scanline rasterizer in 32 × 32 tiles, colors interpolated
//               perspective-correctly, at the points of the aa mode's sample grid
//               (camera/sample_grid.h), or for jittered samples once per pass at the image's
//               own size with the pass's sub-pixel offset (camera/accumulation_buffer.h).
//   ray-traced  a ray through each sample point; at its hit, the vertex radiosities of the
//               element hit interpolated at the point (the Gouraud field without its screen-space
//               interpolation).
//   elements    the element mesh (000 Figure 65): each element flat, its edges drawn dark.
// Pixels no surface covers show the background. Each sample depends only on the solution and its
// own ray or grid tile, so the image does not depend on the thread count.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "accel/accelerator.h"
#include "camera/accumulation_buffer.h"
#include "camera/antialiasing.h"
#include "camera/film.h"
#include "camera/sample_grid.h"
#include "radiosity/radiosity_settings.h"
#include "radiosity/radiosity_solve_result.h"
#include "radiosity/vertex_radiosity.h"
#include "raster/rasterizer.h"

namespace candela {

class Scene;

class SolutionDisplay {
 public:
  // Prepares the view once: the vertex radiosities (gouraud, ray-traced) and, for gouraud, the
  // elements projected (tiles across ranks do not redo it). The scene and the solution
  // must outlive the display. The samples are placed by `antialiasing` with `seed`: the render's,
  // which need not be the scene's (RenderRequest::seed, antialiasing).
  SolutionDisplay(const Scene& scene, const RadiositySolveResult& solution, RadiosityDisplay display,
                  const AntialiasingSettings& antialiasing, uint64_t seed);

  // Draws the pixels [x0, x0 + film.width()) × [y0, y0 + film.height()) of the camera's image
  // into film; returns the samples taken (rays, or grid samples for gouraud).
  uint64_t draw(int x0, int y0, Film& film) const;

  // Whether a ray goes through every pixel (every display but gouraud, which rasterizes).
  bool casts_primary_rays() const { return display_ != RadiosityDisplay::gouraud; }

 private:
  // The grid samples [gx0, gx0 + samples.width()) × [gy0, …) into samples; with an offset (the
  // grid the image's own pixels), each pixel's sample at (x + offset.dx, y + offset.dy).
  void draw_rasterized(int64_t gx0, int64_t gy0, const PassOffset* offset, Film& samples) const;
  // The display along the camera ray through image point (x, y).
  Color ray_cast(double x, double y) const;

  const Scene& scene_;
  const RadiositySolveResult& solution_;
  RadiosityDisplay display_;
  AntialiasingSettings antialiasing_;
  uint64_t seed_;
  bool in_passes_ = false;    // gouraud: jittered samples, drawn in passes
  SampleGrid grid_;           // gouraud: the aa mode's grid, or in passes the image's pixels
  VertexRadiosity vertices_;  // gouraud, ray-traced
  // gouraud: every element's triangle in clip space (the grid's: camera/sample_grid.h), and its
  // bounds on the grid (unbounded when a corner is behind the near plane).
  std::vector<std::array<RasterVertex, 3>> triangles_;
  std::vector<ScreenBounds> bounds_on_screen_;
};

// The radiosity the ray-traced display shows at a hit on `element`: the element's vertex
// radiosities interpolated at the hit point's barycentric coordinates.
Color ray_traced_radiosity(const RadiositySolveResult& solution, const VertexRadiosity& vertices,
                           uint32_t element, const Intersection& hit);

}  // namespace candela
