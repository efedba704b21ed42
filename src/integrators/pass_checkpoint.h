// The state of a method rendered in passes (integrators/pass_method.h: the path tracer) as a
// checkpoint (SPEC §15: long runs checkpoint and resume): the per-pixel sums of every pass so far
// (Σ w·L and Σ w of the reconstruction filter), exactly as doubles, so that resuming and finishing
// gives the image an uninterrupted run gives, bit for bit (each pixel's passes are added in pass
// order either way). Sealed in the byte format of io/checkpoint_file.h (which the caller writes
// to a file and reads back) under a magic line naming the method ("CANDELA-PATH-CHECKPOINT 2");
// unsealed with its size and checksum verified.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "integrators/method.h"
#include "io/checkpoint_file.h"
#include "math/vector.h"
#include "util/statistics.h"

namespace candela {

struct PassCheckpoint {
  // What the sums belong to: the scene, the camera and every setting that changes a sample.
  std::string fingerprint;
  PixelRect region;
  uint64_t passes = 0;
  double seconds = 0;  // rendering time spent so far (all runs together)
  RayCounts rays;
  std::vector<Color> sums;      // Σ w·L: region.width() × region.height(), row by row
  std::vector<double> weights;  // Σ w of the reconstruction filter (the pass count for the box)
};

// `method`: the method's name, which the magic line spells ("path").
Bytes seal_pass_checkpoint(std::string_view method, const PassCheckpoint& checkpoint);
// Throws InputError naming the checkpoint's source when it is truncated, corrupt or not this
// method's checkpoint.
PassCheckpoint unseal_pass_checkpoint(std::string_view method, const SealedCheckpoint& sealed);

}  // namespace candela
