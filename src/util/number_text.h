// A number as text files write it (IES and EULUMDAT photometry): an optional sign — a leading
// '+' too, which std::from_chars refuses — digits, a point, an exponent, and nothing else; the
// value must be finite.
#pragma once

#include <charconv>
#include <cmath>
#include <string_view>

namespace candela {

inline bool parse_finite_number(std::string_view text, double& value) {
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  // from_chars itself refuses a second sign ("++1", "+-1") and an empty text.
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  return error == std::errc() && end == text.data() + text.size() && std::isfinite(value);
}

}  // namespace candela
