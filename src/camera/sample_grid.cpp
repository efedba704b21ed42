#include "camera/sample_grid.h"

namespace candela {

std::optional<SampleGrid> sample_grid(const AntialiasingSettings& settings) {
  switch (settings.mode) {
    case AntialiasingMode::none:
      return SampleGrid{1, false};
    case AntialiasingMode::uniform:
      return SampleGrid{settings.n, false};
    case AntialiasingMode::jittered:
      return std::nullopt;
    case AntialiasingMode::corners:
      if (settings.jitter) return std::nullopt;
      return SampleGrid{1, true};
    case AntialiasingMode::adaptive:
      if (settings.jitter) return std::nullopt;
      return SampleGrid{1 << settings.max_level, true};
  }
  return std::nullopt;
}

}  // namespace candela
