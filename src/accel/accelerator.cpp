#include "accel/accelerator.h"

#include <fmt/format.h>

namespace candela {

std::string AcceleratorReport::text() const {
  std::string text;
  for (const auto& [name, value] : figures) text += fmt::format("{} {:.6g}, ", name, value);
  text += fmt::format("{:.2f} MiB", bytes / (1024.0 * 1024.0));
  return text;
}

}  // namespace candela
