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

// The refusal of a view that rasterizes (camera/sample_grid.h): jittered samples, a jittered
// lattice, and a grid too large to hold (aa.n, aa.max_level) for the scene's camera or any of its
// named cameras (the views of candela render --camera).
std::optional<AntialiasingRefusal> sample_grid_refusal(const AntialiasingSettings& settings,
                                                       const Scene& scene);

// "raster cannot do aa.mode \"adaptive\" (…)".
std::string describe_refusal(std::string_view method, const AntialiasingRefusal& refusal);

}  // namespace candela
