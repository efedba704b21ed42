#include "radiosity/form_factor_memory.h"

#include <fmt/format.h>

#include "radiosity/solvers.h"
#include "util/memory.h"

namespace candela {

uint64_t form_factor_memory_limit(const RadiositySettings& settings) {
  return memory_limit_bytes(settings.memory_limit_mib);
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
