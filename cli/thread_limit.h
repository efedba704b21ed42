// --threads N of the sub-commands that compute (render, probe, validate): N worker threads while
// the limit lives, all cores for 0 (the default).
#pragma once

#include <tbb/global_control.h>

#include <cstddef>
#include <optional>

#include "commands.h"

namespace candela::cli {

// Throws BadArgument for N < 0.
inline void limit_threads(int threads, std::optional<tbb::global_control>& limit) {
  if (threads < 0) throw BadArgument("--threads must be >= 0 (0: all cores)");
  if (threads > 0)
    limit.emplace(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
}

}  // namespace candela::cli
