#pragma once

#include <memory>
#include <span>
#include <string_view>

#include "integrators/method.h"

namespace candela {

struct MethodEntry {
  std::string_view name;
  std::string_view description;
  std::unique_ptr<Method> (*create)();
};

std::span<const MethodEntry> method_entries();
const MethodEntry* find_method(std::string_view name);
std::string method_names();  // "local, whitted"

}  // namespace candela
