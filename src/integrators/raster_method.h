// The `raster` method (SPEC §9; 000 §3): the scene tessellated (Shape::tessellate), drawn by the
// scanline z-buffer rasterizer and shaded with the same local model and lights as the ray
// tracer (src/integrators/direct_lighting.h), in one of four modes (setting raster.shading):
//
//   flat        one intensity per triangle: the local model at its centroid with its face
//               normal (000 §3.1) — Mach bands at every edge (000 §3.1.1);
//   gouraud     the local model at the vertices with the averaged vertex normals, intensities
//               interpolated across the triangle, incrementally along each scanline
//               (000 §3.2: I_p2 = I_p1 + ΔI·Δv) — a highlight inside a triangle is lost;
//   phong       normals (and positions, uvs) interpolated, the local model per pixel (000 §3.3);
//   dotproduct  N·L and the specular term of each light interpolated, combined per pixel with
//               the material and the light's intensity there (000 §3.4, "reduced Phong").
//
// Vertex normals average the adjacent face normals of the same object, except across edges
// sharper than raster.crease_angle (000 §3.2.1: two normals at a vertex). Shading is deferred:
// the rasterizer keeps the nearest triangle's interpolated values per pixel and each pixel is
// shaded once, so the image does not depend on the drawing order of hidden triangles or on the
// thread count. Surfaces are two-sided; uncovered pixels show the background or environment.
// Anti-aliasing (the scene's "aa"): the scene is drawn at the points of the mode's sample grid —
// the pixel centres (none), the image at n× (uniform), the corner lattice of spacing
// 2^-max_level (corners, adaptive: every lattice point is drawn, adaptive reads those its
// subdivision asks for) — and sample_image reconstructs the pixels from them with the scene's
// filter, as it does the ray tracers' samples. Jittered samples lie off any grid: the image is
// drawn once per pass with its projection moved by the pass's sub-pixel offset, and the passes
// are splatted into the film (the accumulation buffer, camera/accumulation_buffer.h).
// Not drawn here: reflection, refraction, the see-through blend, bump mapping (ray tracing's).
#pragma once

#include "integrators/method.h"
#include "io/json_node.h"
#include "util/enum_names.h"

namespace candela {

enum class RasterShading { flat, gouraud, phong, dot_product };
inline constexpr auto kRasterShadingNames =
    enum_names<RasterShading>({{RasterShading::flat, "flat"},
                               {RasterShading::gouraud, "gouraud"},
                               {RasterShading::phong, "phong"},
                               {RasterShading::dot_product, "dotproduct"}});

// The scene file's "raster" object.
struct RasterSettings {
  RasterShading shading = RasterShading::phong;
  int segments = 32;         // tessellation: divisions of a full turn
  double crease_angle = 60;  // degrees: sharper edges keep two normals at a vertex
  bool shadows = false;      // shadow rays from the shaded points (through the accelerator)
};
RasterSettings read_raster_settings(const JsonNode& node);

class RasterMethod final : public Method {
 public:
  explicit RasterMethod(const RasterSettings& settings = {}) : settings_(settings) {}
  std::string_view name() const override { return "raster"; }
  bool rasterizes() const override { return true; }
  RenderResult render(const Scene& scene, const RenderRequest& request) const override;
  // Every aa mode and filter: the modes whose samples lie on a grid (camera/sample_grid.h) drawn
  // on it, the jittered ones in passes (camera/accumulation_buffer.h); refused only a grid too
  // large to hold.
  std::optional<AntialiasingRefusal> antialiasing_refusal(
      const Scene& scene, const AntialiasingSettings& antialiasing) const override;
  // "dotproduct" shading and the environment, or more lights than it interpolates.
  void refuse_scene(const Scene& scene) const override;
  // The image, the grid's samples and the view's triangles.
  std::vector<MemoryPart> memory_needed(const Scene& scene, const RenderRequest& request) const override;

 private:
  RasterSettings settings_;
};

}  // namespace candela
