#include "radiosity/radiosity_checkpoint.h"

#include "io/checkpoint_file.h"

namespace candela {

namespace {
constexpr char kMagic[] = "CANDELA-RADIOSITY-CHECKPOINT 1\n";
}  // namespace

void write_radiosity_checkpoint(const std::string& path, const RadiosityCheckpoint& checkpoint) {
  CheckpointWriter out(kMagic);
  out.put_string(checkpoint.fingerprint);
  out.put(checkpoint.steps);
  out.put_colors(checkpoint.radiosity);
  out.put_colors(checkpoint.unshot);
  out.write(path);
}

RadiosityCheckpoint read_radiosity_checkpoint(const std::string& path) {
  CheckpointReader in(path, kMagic);
  RadiosityCheckpoint checkpoint;
  checkpoint.fingerprint = in.get_string();
  checkpoint.steps = in.get<uint64_t>();
  checkpoint.radiosity = in.get_colors();
  checkpoint.unshot = in.get_colors();
  in.finish();
  return checkpoint;
}

}  // namespace candela
