// Progressive radiosity's state as a checkpoint (it resumes
// to the same result as an uninterrupted run): the element radiosities B and the patches' unshot
// radiosities ΔB after some number of shots. The mesh and the form factors are not stored: they
// follow from the scene and its settings and are computed again on resume (the fingerprint ties
// the state to them); the shots then continue from exactly this state, so the result is the
// uninterrupted run's, bit for bit. Sealed in the byte format of io/checkpoint_file.h.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "io/checkpoint_file.h"
#include "math/vector.h"

namespace candela {

struct RadiosityCheckpoint {
  std::string fingerprint;
  uint64_t steps = 0;            // shots so far
  std::vector<Color> radiosity;  // B per element
  std::vector<Color> unshot;     // ΔB per patch
};

Bytes seal_radiosity_checkpoint(const RadiosityCheckpoint& checkpoint);
// InputError naming the checkpoint's source when it is damaged or another kind of checkpoint.
RadiosityCheckpoint unseal_radiosity_checkpoint(const SealedCheckpoint& sealed);

}  // namespace candela
