#include "radiosity/radiosity_checkpoint.h"

namespace candela {

namespace {
constexpr char kMagic[] = "CANDELA-RADIOSITY-CHECKPOINT 1\n";
}  // namespace

Bytes seal_radiosity_checkpoint(const RadiosityCheckpoint& checkpoint) {
  CheckpointWriter out(kMagic);
  out.put_string(checkpoint.fingerprint);
  out.put(checkpoint.steps);
  out.put_colors(checkpoint.radiosity);
  out.put_colors(checkpoint.unshot);
  return out.seal();
}

RadiosityCheckpoint unseal_radiosity_checkpoint(const SealedCheckpoint& sealed) {
  CheckpointReader in(sealed, kMagic);
  RadiosityCheckpoint checkpoint;
  checkpoint.fingerprint = in.get_string();
  checkpoint.steps = in.get<uint64_t>();
  checkpoint.radiosity = in.get_colors();
  checkpoint.unshot = in.get_colors();
  in.finish();
  return checkpoint;
}

}  // namespace candela
