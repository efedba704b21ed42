// A radiosity solution drawn for the scene's camera (000 §6.5, SPEC §10 "Display"; setting
// radiosity.display):
//   flat        one ray through each pixel centre; its hit → the element of the hit primitive
//               nearest the hit point → that element's radiosity B (the exitance, view
//               independent), shown directly as the seed's radiosity images are.
//   gouraud     the vertex radiosities of radiosity/vertex_radiosity.h; the elements drawn as
//               triangles by the scanline rasterizer in 32 × 32 tiles, colors interpolated
//               perspective-correctly.
//   ray-traced  a ray through each pixel centre; at its hit, the vertex radiosities of the
//               element hit interpolated at the point (the Gouraud field without its screen-space
//               interpolation).
//   elements    the element mesh (000 Figure 65): each element flat, its edges drawn dark.
// Pixels no surface covers show the background. Each pixel depends only on the solution and its
// own ray or tile, so the image does not depend on the thread count.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "accel/accelerator.h"
#include "camera/film.h"
#include "radiosity/radiosity_settings.h"
#include "radiosity/radiosity_solve_result.h"
#include "radiosity/vertex_radiosity.h"
#include "raster/rasterizer.h"

namespace candela {

class Scene;

class SolutionDisplay {
 public:
  // Prepares the view once: the vertex radiosities (gouraud, ray-traced) and, for gouraud, the
  // elements projected (tiles across ranks, issue 11, do not redo it). The scene and the solution
  // must outlive the display.
  SolutionDisplay(const Scene& scene, const RadiositySolveResult& solution, RadiosityDisplay display);

  // Draws the pixels [x0, x0 + film.width()) × [y0, y0 + film.height()) of the camera's image
  // into film.
  void draw(int x0, int y0, Film& film) const;

  // Whether a ray goes through every pixel (every display but gouraud, which rasterizes).
  bool casts_primary_rays() const { return display_ != RadiosityDisplay::gouraud; }

 private:
  void draw_rasterized(int x0, int y0, Film& film) const;
  void draw_ray_cast(int x0, int y0, Film& film) const;

  const Scene& scene_;
  const RadiositySolveResult& solution_;
  RadiosityDisplay display_;
  VertexRadiosity vertices_;  // gouraud, ray-traced
  // gouraud: every element's triangle in clip space, and its screen bounds (unbounded when a
  // corner is behind the near plane).
  std::vector<std::array<RasterVertex, 3>> triangles_;
  std::vector<ScreenBounds> bounds_on_screen_;
};

// The radiosity the ray-traced display shows at a hit on `element`: the element's vertex
// radiosities interpolated at the hit point's barycentric coordinates.
Color ray_traced_radiosity(const RadiositySolveResult& solution, const VertexRadiosity& vertices,
                           uint32_t element, const Intersection& hit);

}  // namespace candela
