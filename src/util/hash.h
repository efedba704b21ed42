// FNV-1a (Fowler, Noll, Vo), 64-bit: a fast fingerprint of bytes — what ties a checkpoint to its
// scene and catches a damaged file; not for adversaries. And splitmix64's finaliser (Steele, Lea,
// Flood 2014): 64 bits mixed so that every input bit reaches every output bit — the hash behind
// values that must be a pure function of a key (lattice jitter, per-pass seeds, light jitter).
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

constexpr uint64_t mix64(uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

}  // namespace candela
