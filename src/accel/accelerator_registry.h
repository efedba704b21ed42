// The accelerators by name (render.accelerator). Each entry reads its own settings from its
// object of the scene file ("bvh": {...}, "grid": {...}, "octree": {...}; an empty object gives
// its defaults), refusing unknown keys and values out of range.
#pragma once

#include <memory>
#include <span>
#include <string>
#include <string_view>

#include "accel/accelerator.h"
#include "io/json_node.h"

namespace candela {

struct AcceleratorEntry {
  std::string_view name;
  std::string_view description;
  // settings: the scene file's object named after the accelerator; object_volume: what the list
  // tests per scene object first (render.bounding_volume; the other structures bound primitives).
  std::unique_ptr<Accelerator> (*create)(const JsonNode& settings, BoundingVolumeKind object_volume);
  // Whether it keeps the contract of accel/accelerator.h (the list's hits, to the last bit);
  // false only for bvh-fast, which trades it for speed.
  bool exact = true;
};

std::span<const AcceleratorEntry> accelerator_entries();
// nullptr for an unknown name.
const AcceleratorEntry* find_accelerator(std::string_view name);
// The accelerator with its default settings (benchmarks, tests).
std::unique_ptr<Accelerator> create_default_accelerator(
    const AcceleratorEntry& entry, BoundingVolumeKind object_volume = BoundingVolumeKind::none);

}  // namespace candela
