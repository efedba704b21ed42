// A method rendered in passes over its pixels, each pass adding one sample's worth to every
// pixel's sums (Σ w·L and Σ w of the film's filter), until path.spp-like passes or a time limit
// (SPEC §12, §15): the path tracer, and any progressive image method. The method supplies only
// what is its own — one pass over some pixels (PixelPasses), the settings that shape a pass (its
// fingerprint) and those that say how far to run (RunLimits) — and the driver here does the rest
// for it: checkpoints and resume (integrators/pass_checkpoint.h, through ProgressiveRun), the
// passes on one process or in rounds of tiles across ranks, the progress line, Ctrl-C, the
// request's per-pass callbacks (the error log) and the facts of the run.
#pragma once

#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "camera/splat_film.h"
#include "integrators/method.h"
#include "integrators/progressive_run.h"
#include "util/statistics.h"

namespace candela {

// One render's passes: the method's state for the render (its samplers, its light sampler) and
// the work of one pass.
class PixelPasses {
 public:
  virtual ~PixelPasses() = default;
  // Adds pass `pass` over `pixels` (region coordinates) into sums and weights (pixels-sized, row by
  // row), each pixel's terms in a fixed order, so that a tile of them on another rank adds the very
  // same bits; non-finite samples of the pixels are counted into `dropped`. False, leaving sums
  // and weights as they were, when Ctrl-C cut the pass short.
  virtual bool run_pass(uint64_t pass, const PixelBox& pixels, Color* sums, double* weights,
                        uint64_t& dropped) = 0;
  // The rays traced so far by this process.
  virtual RayCounts rays() const = 0;
  // The method's own facts of the run (its settings, what it lit the scene with).
  virtual void add_facts(nlohmann::json& facts) const { (void)facts; }
};

class PassMethod : public Method {
 public:
  RenderResult render(const Scene& scene, const RenderRequest& request) const final;
  // The image, a pass's, the running sums and weights and their checkpoint.
  std::vector<MemoryPart> memory_needed(const Scene& scene, const RenderRequest& request) const override;

 protected:
  // The method's settings that change a pass (not how far to run), for the checkpoint's
  // fingerprint; the driver adds the request's part, the seed and the image size.
  virtual std::string pass_fingerprint() const = 0;
  virtual RunLimits limits() const = 0;
  // The passes of one render of the request.
  virtual std::unique_ptr<PixelPasses> start_passes(const Scene& scene,
                                                    const RenderRequest& request) const = 0;
};

}  // namespace candela
