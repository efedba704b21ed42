// A rendering method (local, whitted, later raster, radiosity, meshless, path), found by name
// in the method registry. A method reads the Scene; it never edits it.
#pragma once

#include <string>
#include <string_view>

#include "camera/film.h"
#include "scene/scene.h"
#include "util/statistics.h"

namespace candela {

class Cluster;

// The pixels to render: [x0, x1) × [y0, y1) of the camera's image.
struct PixelRect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  int width() const { return x1 - x0; }
  int height() const { return y1 - y0; }
};

struct RenderRequest {
  PixelRect region;
  bool quiet = false;
  // Where a method that computes a view-independent solution writes it (radiosity: .csv, .ply
  // or .gltf, radiosity/solution_export.h); empty: nowhere. Other methods ignore it.
  std::string export_solution = {};
  // Where the meshless method writes the image with its sites drawn over it (seed 002 Figure 4.7);
  // empty: nowhere. Other methods ignore it.
  std::string show_sites = {};
  // The path tracer's progressive run (SPEC §12, §15): the file it writes its state to every
  // path.checkpoint_interval seconds and when it ends, the checkpoint it continues from, and what
  // ties a checkpoint to the scene that made it (the caller's part: the scene file's contents and
  // overrides; the method adds its own settings). Empty: none. Other methods ignore them.
  std::string checkpoint = {};
  std::string resume = {};
  std::string fingerprint = {};
  // Seconds between checkpoints; 0: the method's default (path.checkpoint_interval; 60 for
  // progressive radiosity, which also checkpoints to `checkpoint` and resumes from `resume`).
  double checkpoint_interval = 0;
  // The ranks to split the work across (issue 11, docs/distributed.md); null or one rank: this
  // process alone. Every rank calls render with the same scene and request; rank 0's film holds
  // the image, and only rank 0 writes files (checkpoints, exports). Statistics are totals over
  // the ranks.
  Cluster* cluster = nullptr;
};

class Method {
 public:
  virtual ~Method() = default;
  virtual std::string_view name() const = 0;
  // Fills film (region-sized) and adds to statistics.
  virtual void render(const Scene& scene, const RenderRequest& request, Film& film,
                      RunStatistics& statistics) const = 0;
};

}  // namespace candela
