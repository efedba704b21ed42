// FNV-1a (Fowler, Noll, Vo), 64-bit: a fast fingerprint of bytes — what ties a checkpoint to its
// scene and catches a damaged file; not for adversaries.
#pragma once

#include <cstdint>
#include <string_view>

namespace candela {

constexpr uint64_t fnv1a_64(std::string_view bytes) {
  uint64_t hash = 1469598103934665603ULL;
  for (const char c : bytes) {
    hash ^= static_cast<unsigned char>(c);
    hash *= 1099511628211ULL;
  }
  return hash;
}

}  // namespace candela
