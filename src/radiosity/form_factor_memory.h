// The memory the radiosity solve's stored form factors may take (setting
// radiosity.memory_limit_mib, SPEC §10): what the element rows and the full patch matrix need, and
// the refusal, before anything is allocated, of a solve that would need more (refused
// with a message naming the setting to change).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "radiosity/radiosity_settings.h"

namespace candela {

// radiosity.memory_limit_mib in bytes, or half the machine's memory when it is 0.
uint64_t form_factor_memory_limit(const RadiositySettings& settings);

// Throws SolverMemoryError (radiosity/solvers.h) when `required` bytes exceed the limit; the
// message says what needs them (`what`), the remedy, and radiosity.memory_limit_mib.
void check_form_factor_memory(uint64_t required, const RadiositySettings& settings, const std::string& what,
                              const std::string& remedy);

// The bytes of the element rows F_qj (ElementToPatch: a float per element and patch).
uint64_t element_rows_bytes(std::size_t elements, std::size_t patches);

}  // namespace candela
