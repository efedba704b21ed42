#include "sampling/sobol_sampler.h"

#include "util/hash.h"

namespace candela {

uint32_t sobol_dimension_0(uint32_t index) {
  return reverse_bits(index);
}

uint32_t sobol_dimension_1(uint32_t index) {
  return sobol_detail::kDimension1(index);
}

uint32_t nested_uniform_scramble(uint32_t x, uint32_t seed) {
  return reverse_bits(sobol_detail::laine_karras_permutation(reverse_bits(x), seed));
}

void SobolSampler::start_pixel_sample(uint32_t x, uint32_t y, uint64_t index) {
  const uint64_t key = pixel_sample_key(seed_, x, y);
  pixel_seed_ = static_cast<uint32_t>(key ^ (key >> 32));
  reversed_index_ = reverse_bits(static_cast<uint32_t>(index));  // 2^32 passes of one pixel would repeat
  dimension_ = 0;
}

}  // namespace candela
