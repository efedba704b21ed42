#include "integrators/pass_checkpoint.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>

namespace candela {

namespace {
// Version 2: with the filter weights.
std::string magic(std::string_view method) {
  std::string name(method);
  std::transform(name.begin(), name.end(), name.begin(), [](unsigned char c) { return std::toupper(c); });
  return fmt::format("CANDELA-{}-CHECKPOINT 2\n", name);
}
}  // namespace

Bytes seal_pass_checkpoint(std::string_view method, const PassCheckpoint& checkpoint) {
  CheckpointWriter out(magic(method));
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

PassCheckpoint unseal_pass_checkpoint(std::string_view method, const SealedCheckpoint& sealed) {
  CheckpointReader in(sealed, magic(method));
  PassCheckpoint checkpoint;
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
