// Which anti-aliasing settings (the scene's "aa" object) a method can honour (SPEC §17: every
// image-producing method gets its pixels from the one camera sampling and reconstruction, or
// refuses a mode it cannot do — never a silent fallback). A method says why it cannot; the
// refusal is an InputError naming the method, the setting and its value, given by create_method
// (integrators/method_registry.h) before any work.
#pragma once

#include <optional>
#include <string>

#include "camera/antialiasing.h"
#include "camera/camera.h"

namespace candela {

class Scene;

struct AntialiasingRefusal {
  std::string key;     // "aa.mode", "aa.jitter", "aa.filter", "aa.n", …
  std::string value;   // as the scene file writes it: "\"adaptive\"", "true"
  std::string reason;  // why, and what the method can do instead
};

// The refusal of a view that rasterizes (camera/sample_grid.h): a grid too large to hold (aa.n,
// aa.max_level) for the scene's camera or any of its named cameras (the views of candela render
// --camera). Jittered samples and jittered lattices it draws in passes of the image's own size
// (camera/accumulation_buffer.h): none.
std::optional<AntialiasingRefusal> sample_grid_refusal(const AntialiasingSettings& settings,
                                                       const Scene& scene);

// "raster cannot do aa.mode \"adaptive\" (…)".
std::string describe_refusal(std::string_view method, const AntialiasingRefusal& refusal);

class Method;

// pbrt's --spp N for a method without passes (candela render --spp, candela.render(spp=)):
// n×n = N anti-aliasing samples per pixel. Sets settings.n; keeps settings.mode when it is
// "uniform" or "jittered", otherwise sets "uniform", which every method can do, and returns true:
// the mode is then chosen by choose_jittered_where_possible once the method is made. Throws
// std::invalid_argument when N is not a square in [1, 64²] ("whitted takes n×n samples per pixel
// (aa.n); use 4 or 9"). On a value, so that a render may take its own settings
// (RenderRequest::antialiasing) and leave the scene's alone.
bool set_samples_per_pixel(AntialiasingSettings& settings, std::string_view method, int samples);
// The same on the scene's own "aa" settings (candela render --spp).
bool set_samples_per_pixel(Scene& scene, std::string_view method, int samples);
// settings.mode "jittered" when the method traces a ray through each sample, "uniform" when it
// rasterizes (Method::rasterizes: its n× grid in one drawing rather than n² passes) or cannot
// place jittered samples.
void choose_jittered_where_possible(AntialiasingSettings& settings, const Scene& scene, const Method& method);
// The same on the scene's own "aa" settings.
void choose_jittered_where_possible(Scene& scene, const Method& method);

}  // namespace candela
