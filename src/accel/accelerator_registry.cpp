#include "accel/accelerator_registry.h"

#include <array>

#include "accel/primitive_list.h"

namespace candela {

namespace {
const std::array kEntries = {
    AcceleratorEntry{"list", "brute force: every ray against every primitive",
                     []() -> std::unique_ptr<Accelerator> { return std::make_unique<PrimitiveList>(); }},
};
}  // namespace

std::span<const AcceleratorEntry> accelerator_entries() { return kEntries; }

const AcceleratorEntry* find_accelerator(std::string_view name) {
  for (const auto& entry : kEntries)
    if (entry.name == name) return &entry;
  return nullptr;
}

}  // namespace candela
