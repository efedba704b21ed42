#include <array>
#include <stdexcept>

#include "sampling/independent_sampler.h"
#include "sampling/sampler.h"
#include "sampling/sobol_sampler.h"
#include "sampling/stratified_sampler.h"

namespace candela {

namespace {

constexpr std::array<SamplerEntry, 3> kSamplerEntries{{
    {"independent", "independent PCG32 numbers per pixel and pass", false,
     [](const SamplerParameters& p) -> std::unique_ptr<Sampler> {
       return std::make_unique<IndependentSampler>(p.seed);
     }},
    {"stratified", "each dimension jittered in path.spp strata, taken by the passes in a shuffled order",
     true,
     [](const SamplerParameters& p) -> std::unique_ptr<Sampler> {
       return std::make_unique<StratifiedSampler>(p.seed, p.samples);
     }},
    {"sobol", "Owen-scrambled Sobol' points (Burley 2020), a (0, 2)-sequence in every pair of dimensions",
     false,
     [](const SamplerParameters& p) -> std::unique_ptr<Sampler> {
       return std::make_unique<SobolSampler>(p.seed);
     }},
}};

}  // namespace

std::span<const SamplerEntry> sampler_entries() {
  return kSamplerEntries;
}

const SamplerEntry* find_sampler(std::string_view name) {
  for (const SamplerEntry& entry : kSamplerEntries)
    if (name == entry.name) return &entry;
  return nullptr;
}

std::string sampler_names() {
  std::string names;
  for (const SamplerEntry& entry : kSamplerEntries)
    names += (names.empty() ? "" : ", ") + std::string(entry.name);
  return names;
}

std::unique_ptr<Sampler> create_sampler(std::string_view name, const SamplerParameters& parameters) {
  const SamplerEntry* entry = find_sampler(name);
  if (!entry)
    throw std::invalid_argument("unknown sampler \"" + std::string(name) + "\" (known: " + sampler_names() +
                                ")");
  if (entry->needs_sample_count && parameters.samples == 0)
    throw std::invalid_argument("the \"" + std::string(name) +
                                "\" sampler needs the number of samples per pixel (path.spp), not a time");
  return entry->create(parameters);
}

}  // namespace candela
