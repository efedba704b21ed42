// The independent sampler: every value a fresh PCG32 number, the stream of the sample's pixel and
// pass (what the path tracer drew before it had samplers).
#pragma once

#include "math/pcg32.h"
#include "sampling/sampler.h"

namespace candela {

// The stream of pass `pass` of pixel (x, y) under `seed`.
Pcg32 independent_stream(uint64_t seed, uint64_t pass, uint32_t x, uint32_t y);

class IndependentSampler final : public Sampler {
 public:
  explicit IndependentSampler(uint64_t seed) : seed_(seed) {}
  // A sampler that draws from a stream the caller set up (a lattice point's, a probe's).
  explicit IndependentSampler(const Pcg32& stream) : stream_(stream) {}

  std::string_view name() const override { return "independent"; }
  void start_pixel_sample(uint32_t x, uint32_t y, uint64_t index) override {
    stream_ = independent_stream(seed_, index, x, y);
  }
  double get_1d() override { return stream_.next_double(); }
  Vec2 get_2d() override {
    const double u = stream_.next_double();
    return {u, stream_.next_double()};
  }
  std::unique_ptr<Sampler> clone() const override { return std::make_unique<IndependentSampler>(*this); }
  const Pcg32& stream() const { return stream_; }

 private:
  uint64_t seed_ = 0;
  Pcg32 stream_;
};

}  // namespace candela
