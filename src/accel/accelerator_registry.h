#pragma once

#include <memory>
#include <span>
#include <string>
#include <string_view>

#include "accel/accelerator.h"

namespace candela {

struct AcceleratorEntry {
  std::string_view name;
  std::string_view description;
  std::unique_ptr<Accelerator> (*create)(const AcceleratorSettings& settings);
};

std::span<const AcceleratorEntry> accelerator_entries();
// nullptr for an unknown name.
const AcceleratorEntry* find_accelerator(std::string_view name);

}  // namespace candela
