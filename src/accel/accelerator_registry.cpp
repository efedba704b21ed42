#include "accel/accelerator_registry.h"

#include <array>

#include "accel/primitive_list.h"

#include "util/registry.h"

namespace candela {

namespace {
const std::array kEntries = {
    AcceleratorEntry{"list", "brute force: every ray against every primitive",
                     [](const AcceleratorSettings& settings) -> std::unique_ptr<Accelerator> {
                       return std::make_unique<PrimitiveList>(settings.bounding_volume);
                     }},
};
}  // namespace

std::span<const AcceleratorEntry> accelerator_entries() { return kEntries; }

const AcceleratorEntry* find_accelerator(std::string_view name) { return find_entry<AcceleratorEntry>(kEntries, name); }

}  // namespace candela
