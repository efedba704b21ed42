// Keeps sites at least Δ apart (site distance, site.h) in the order they are offered — the pruning
// of the site sampling (seed 002 §4.2.6) and the Poisson-disc thinning of each level of the site
// hierarchy. A hash grid of cells Δ wide holds the kept ones, and since
// ||p, q|| ≥ |ṗ − q̇| only the 27 cells around a candidate can hold one closer than Δ.
#pragma once

#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "meshless/site.h"

namespace candela {

class SpacingFilter {
 public:
  explicit SpacingFilter(double spacing) : spacing_(spacing) {}

  // Keeps site unless a kept one lies closer than Δ; says whether it was kept.
  bool try_keep(const Site& site) {
    const int64_t cx = cell(site.position.x), cy = cell(site.position.y), cz = cell(site.position.z);
    for (int64_t x = cx - 1; x <= cx + 1; ++x)
      for (int64_t y = cy - 1; y <= cy + 1; ++y)
        for (int64_t z = cz - 1; z <= cz + 1; ++z) {
          const auto found = cells_.find(key(x, y, z));
          if (found == cells_.end()) continue;
          for (const Site& kept : found->second)
            if (site_distance(site, kept) < spacing_) return false;
        }
    cells_[key(cx, cy, cz)].push_back(site);
    return true;
  }

 private:
  int64_t cell(double value) const { return static_cast<int64_t>(std::floor(value / spacing_)); }
  static uint64_t key(int64_t x, int64_t y, int64_t z) {
    return (static_cast<uint64_t>(x) & 0x1FFFFF) | (static_cast<uint64_t>(y) & 0x1FFFFF) << 21 |
           (static_cast<uint64_t>(z) & 0x1FFFFF) << 42;
  }
  double spacing_;
  std::unordered_map<uint64_t, std::vector<Site>> cells_;
};

}  // namespace candela
