// A k-d tree over the positions of a set of sites (nanoflann, SPEC §16), answering the queries the
// meshless bases and the site sampling need in terms of the site distance of site.h:
//   - the sites within a site distance of a query site (every site within that Euclidean
//     distance is a candidate, since ||p, q|| ≥ |ṗ − q̇|);
//   - the m nearest sites by site distance (Euclidean neighbours fetched in growing numbers until
//     the m-th site distance is no larger than the farthest Euclidean distance fetched).
// Built once; the sites must outlive the index. Queries are thread-safe.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "meshless/site.h"

namespace candela {

class SiteIndex {
 public:
  explicit SiteIndex(std::span<const Site> sites);
  ~SiteIndex();
  SiteIndex(SiteIndex&&) noexcept;
  SiteIndex& operator=(SiteIndex&&) noexcept;

  std::size_t size() const { return sites_.size(); }

  // Appends to out the indices of the sites within Euclidean distance `radius` of point
  // (inclusive), in increasing index order.
  void within_euclidean(const Vec3& point, double radius, std::vector<uint32_t>& out) const;

  // The site distance from site to its m-th nearest site among the others (by site distance;
  // `self` is skipped, pass UINT32_MAX when site is not one of the set); infinity when fewer than
  // m others are at a finite site distance.
  double mth_nearest_site_distance(const Site& site, std::size_t m, uint32_t self) const;

 private:
  struct Tree;
  std::span<const Site> sites_;
  std::unique_ptr<Tree> tree_;
};

}  // namespace candela
