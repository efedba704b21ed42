// Lookups shared by every registry: an explicit table of entries with a `name` member
// (STYLE.md habit 2).
#pragma once

#include <span>
#include <string>
#include <string_view>

namespace candela {

// nullptr for an unknown name.
template <typename Entry>
const Entry* find_entry(std::span<const Entry> entries, std::string_view name) {
  for (const Entry& entry : entries)
    if (entry.name == name) return &entry;
  return nullptr;
}

// "a, b, c": for "unknown name" messages that list the valid ones.
template <typename Entry>
std::string entry_names(std::span<const Entry> entries) {
  std::string names;
  for (const Entry& entry : entries) {
    if (!names.empty()) names += ", ";
    names += entry.name;
  }
  return names;
}

}  // namespace candela
