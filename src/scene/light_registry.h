#pragma once

#include <memory>
#include <span>
#include <string_view>

#include "io/json_node.h"
#include "scene/light.h"
#include "scene/load_context.h"

namespace candela {

struct LightEntry {
  std::string_view name;
  std::string_view description;
  std::string_view example;
  // Returns nullptr for "ambient", whose intensity is added to ambient instead. Files (a
  // luminaire's photometry) resolve through the context.
  std::unique_ptr<Light> (*create)(const JsonNode& node, Color& ambient, const LoadContext& context);
};

std::span<const LightEntry> light_entries();
const LightEntry* find_light(std::string_view name);

}  // namespace candela
