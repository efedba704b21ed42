// One table of names per enum, read both ways: parsing a setting ("gauss-seidel" → the value)
// and printing it (--stats, messages). Each enum's names are spelled once, in its table.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <utility>

namespace candela {

template <typename Enum, std::size_t N>
class EnumNames {
 public:
  constexpr explicit EnumNames(std::array<std::pair<Enum, std::string_view>, N> entries)
      : entries_(entries) {}

  // The name of a value ("?" for a value not in the table, which a complete table never sees).
  constexpr std::string_view name(Enum value) const {
    for (const auto& [entry, name] : entries_)
      if (entry == value) return name;
    return "?";
  }
  constexpr std::optional<Enum> value(std::string_view name) const {
    for (const auto& [entry, entry_name] : entries_)
      if (entry_name == name) return entry;
    return std::nullopt;
  }
  // "a, b, c": what "unknown value" messages list.
  std::string names() const {
    std::string list;
    for (const auto& [entry, name] : entries_) {
      if (!list.empty()) list += ", ";
      list += name;
    }
    return list;
  }

 private:
  std::array<std::pair<Enum, std::string_view>, N> entries_;
};

// Deduces the table's size: constexpr auto kNames = enum_names<Mode>({{{Mode::a, "a"}, ...}});
template <typename Enum, std::size_t N>
constexpr EnumNames<Enum, N> enum_names(const std::pair<Enum, std::string_view> (&entries)[N]) {
  std::array<std::pair<Enum, std::string_view>, N> table{};
  for (std::size_t i = 0; i < N; ++i) table[i] = entries[i];
  return EnumNames<Enum, N>(table);
}

}  // namespace candela
