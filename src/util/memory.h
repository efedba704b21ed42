// How much memory the machine has: what memory-hungry settings are measured against (SPEC §15:
// a setting that would exceed memory is refused with a message naming it).
#pragma once

#include <cstdint>

namespace candela {

// MemTotal of /proc/meminfo in bytes; 0 when it cannot be read.
uint64_t physical_memory_bytes();

}  // namespace candela
