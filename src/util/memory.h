// How much memory the machine has: what memory-hungry settings are measured against (SPEC §15:
// a setting that would exceed memory is refused with a message naming it).
#pragma once

#include <cstdint>

namespace candela {

// MemTotal of /proc/meminfo in bytes; 0 when it cannot be read.
uint64_t physical_memory_bytes();

// The memory a run may hold (radiosity.memory_limit_mib, render.memory_limit_mib):
// limit_mib mebibytes when it is above 0, else half the machine's memory (8 GiB when that cannot
// be read). Saturates at 2⁶⁴ − 1 bytes.
uint64_t memory_limit_bytes(double limit_mib);

}  // namespace candela
