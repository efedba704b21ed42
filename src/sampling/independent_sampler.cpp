#include "sampling/independent_sampler.h"

#include "util/hash.h"

namespace candela {

Pcg32 independent_stream(uint64_t seed, uint64_t pass, uint32_t x, uint32_t y) {
  // The pass picks the state, the pixel the sequence: streams of different pixels and passes are
  // distinct PCG32 streams.
  return Pcg32(mix64(seed * 0x9e3779b97f4a7c15ULL + pass), (static_cast<uint64_t>(y) << 32) | x);
}

}  // namespace candela
