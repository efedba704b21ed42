// The path tracer's progressive state on disk (SPEC §15: long runs checkpoint and resume): the
// per-pixel sums of every pass so far, exactly as doubles, so that resuming and finishing gives
// the image an uninterrupted run gives, bit for bit (each pixel's passes are added in pass order
// either way). Written atomically (no half-written checkpoint ever replaces a good one); read
// back with its size and checksum verified.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "integrators/method.h"
#include "math/vector.h"
#include "util/statistics.h"

namespace candela {

struct PathCheckpoint {
  // What the sums belong to: the scene, the camera and every setting that changes a sample.
  std::string fingerprint;
  PixelRect region;
  uint64_t passes = 0;
  double seconds = 0;  // rendering time spent so far (all runs together)
  RayCounts rays;
  std::vector<Color> sums;  // region.width() × region.height(), row by row
};

// Throws std::runtime_error when the file cannot be written (the old one, if any, stays).
void write_path_checkpoint(const std::string& path, const PathCheckpoint& checkpoint);
// Throws InputError naming the file when it is missing, truncated, corrupt or not a checkpoint.
PathCheckpoint read_path_checkpoint(const std::string& path);

}  // namespace candela
