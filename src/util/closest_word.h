// The known word nearest a misspelled one, for "unknown command 'rendr' (did you mean render?)"
// by the Levenshtein distance (insertions, deletions, substitutions, each 1).
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace candela {

std::size_t edit_distance(std::string_view a, std::string_view b);

// The first of `words` at the least edit distance from `word`, when that distance is at most
// max(1, |word| / 3) — near enough to be a slip of the fingers; nothing otherwise.
std::optional<std::string> closest_word(std::string_view word, const std::vector<std::string>& words);

}  // namespace candela
