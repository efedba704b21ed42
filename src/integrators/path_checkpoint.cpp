#include "integrators/path_checkpoint.h"

#include <cmath>

namespace candela {

namespace {
constexpr char kMagic[] = "CANDELA-PATH-CHECKPOINT 2\n";  // 2: with the filter weights
}  // namespace

Bytes seal_path_checkpoint(const PathCheckpoint& checkpoint) {
  CheckpointWriter out(kMagic);
  out.put_string(checkpoint.fingerprint);
  for (const int v : {checkpoint.region.x0, checkpoint.region.y0, checkpoint.region.x1, checkpoint.region.y1})
    out.put(static_cast<int32_t>(v));
  out.put(checkpoint.passes);
  out.put(checkpoint.seconds);
  for (const uint64_t count : {checkpoint.rays.primary, checkpoint.rays.shadow, checkpoint.rays.reflected,
                               checkpoint.rays.refracted})
    out.put(count);
  out.put_colors(checkpoint.sums);
  out.put_array(checkpoint.weights);
  return out.seal();
}

PathCheckpoint unseal_path_checkpoint(const SealedCheckpoint& sealed) {
  CheckpointReader in(sealed, kMagic);
  PathCheckpoint checkpoint;
  checkpoint.fingerprint = in.get_string();
  checkpoint.region.x0 = in.get<int32_t>();
  checkpoint.region.y0 = in.get<int32_t>();
  checkpoint.region.x1 = in.get<int32_t>();
  checkpoint.region.y1 = in.get<int32_t>();
  checkpoint.passes = in.get<uint64_t>();
  checkpoint.seconds = in.get<double>();
  checkpoint.rays.primary = in.get<uint64_t>();
  checkpoint.rays.shadow = in.get<uint64_t>();
  checkpoint.rays.reflected = in.get<uint64_t>();
  checkpoint.rays.refracted = in.get<uint64_t>();
  checkpoint.sums = in.get_colors();
  checkpoint.weights = in.get_doubles();
  in.finish();
  const PixelRect& r = checkpoint.region;
  if (r.width() <= 0 || r.height() <= 0 ||
      checkpoint.sums.size() != uint64_t(r.width()) * uint64_t(r.height()) ||
      checkpoint.weights.size() != checkpoint.sums.size())
    in.fail("the checkpoint is corrupt (image size)");
  if (!std::isfinite(checkpoint.seconds) || checkpoint.seconds < 0)
    in.fail("the checkpoint is corrupt (its render time is not a finite number of seconds)");
  return checkpoint;
}

}  // namespace candela
