#include "integrators/method_registry.h"

#include <array>
#include <string>

#include "integrators/local.h"
#include "integrators/whitted.h"

namespace candela {

namespace {
const std::array kEntries = {
    MethodEntry{"local", "ray casting with the local model only (001, 000 §2)",
                []() -> std::unique_ptr<Method> { return std::make_unique<LocalMethod>(); }},
    MethodEntry{"whitted", "recursive Whitted ray tracing (000 §5, 001)",
                []() -> std::unique_ptr<Method> { return std::make_unique<WhittedMethod>(); }},
};
}  // namespace

std::span<const MethodEntry> method_entries() { return kEntries; }

const MethodEntry* find_method(std::string_view name) {
  for (const auto& entry : kEntries)
    if (entry.name == name) return &entry;
  return nullptr;
}

std::string method_names() {
  std::string names;
  for (const auto& entry : kEntries) names += (names.empty() ? "" : ", ") + std::string(entry.name);
  return names;
}

}  // namespace candela
