#include "radiosity/form_factor_memory.h"

#include <fmt/format.h>

#include "radiosity/solvers.h"

namespace candela {

uint64_t form_factor_memory_limit(const RadiositySettings& settings) {
  if (!(settings.memory_limit_mib > 0)) return default_gaussian_elimination_memory_limit();
  const double bytes = settings.memory_limit_mib * 1048576.0;
  // Saturated: beyond 2⁶⁴ bytes the conversion would be undefined.
  return bytes >= 18446744073709549568.0 ? UINT64_MAX : static_cast<uint64_t>(bytes);
}

void check_form_factor_memory(uint64_t required, const RadiositySettings& settings, const std::string& what,
                              const std::string& remedy) {
  const uint64_t limit = form_factor_memory_limit(settings);
  if (required <= limit) return;
  throw SolverMemoryError(settings.location,
                          fmt::format("radiosity: {} needs {:.1f} MiB, more than the {:.1f} MiB allowed; {} "
                                      "(or raise radiosity.memory_limit_mib)",
                                      what, required / 1048576.0, limit / 1048576.0, remedy),
                          required, limit);
}

uint64_t element_rows_bytes(std::size_t elements, std::size_t patches) {
  return static_cast<uint64_t>(elements) * patches * sizeof(float);
}

}  // namespace candela
