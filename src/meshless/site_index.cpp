#include "meshless/site_index.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <nanoflann.hpp>

namespace candela {

struct SiteIndex::Tree {
  // nanoflann's dataset interface over the sites' positions.
  struct Positions {
    std::span<const Site> sites;
    std::size_t kdtree_get_point_count() const { return sites.size(); }
    double kdtree_get_pt(std::size_t index, std::size_t axis) const {
      return sites[index].position[static_cast<int>(axis)];
    }
    template <typename Box>
    bool kdtree_get_bbox(Box&) const {
      return false;  // let nanoflann compute it
    }
  };
  using KdTree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, Positions>,
                                                     Positions, 3, uint32_t>;

  Positions positions;
  KdTree tree;
  explicit Tree(std::span<const Site> sites)
      : positions{sites}, tree(3, positions, nanoflann::KDTreeSingleIndexAdaptorParams(16)) {
    tree.buildIndex();
  }
};

SiteIndex::SiteIndex(std::span<const Site> sites) : sites_(sites) {
  if (!sites.empty()) tree_ = std::make_unique<Tree>(sites);
}
SiteIndex::~SiteIndex() = default;
SiteIndex::SiteIndex(SiteIndex&&) noexcept = default;
SiteIndex& SiteIndex::operator=(SiteIndex&&) noexcept = default;

void SiteIndex::within_euclidean(const Vec3& point, double radius, std::vector<uint32_t>& out) const {
  if (!tree_ || !(radius >= 0)) return;
  const double query[3] = {point.x, point.y, point.z};
  // Called per pixel and per integration sample: the match list is kept per thread.
  thread_local std::vector<std::pair<uint32_t, double>> matches;
  // nanoflann's L2 adaptor works in squared distances; a hair more so that points exactly at the
  // radius are kept despite rounding.
  tree_->tree.radiusSearch(query, radius * radius * (1 + 1e-12), matches,
                           nanoflann::SearchParams(32, 0, false));
  const std::size_t first = out.size();
  for (const auto& [index, distance_squared] : matches)
    if (distance_squared <= radius * radius * (1 + 1e-12)) out.push_back(index);
  std::sort(out.begin() + static_cast<std::ptrdiff_t>(first), out.end());
}

double SiteIndex::mth_nearest_site_distance(const Site& site, std::size_t m, uint32_t self) const {
  const std::size_t others = sites_.size() - (self < sites_.size() ? 1 : 0);
  if (m == 0) return 0;
  if (!tree_ || others < m) return std::numeric_limits<double>::infinity();
  const double query[3] = {site.position.x, site.position.y, site.position.z};
  std::vector<uint32_t> indices;
  std::vector<double> distances_squared;
  std::vector<double> site_distances;
  for (std::size_t fetch = std::min(sites_.size(), 2 * (m + 1));;
       fetch = std::min(sites_.size(), 2 * fetch)) {
    indices.resize(fetch);
    distances_squared.resize(fetch);
    const std::size_t found = tree_->tree.knnSearch(query, fetch, indices.data(), distances_squared.data());
    site_distances.clear();
    for (std::size_t k = 0; k < found; ++k)
      if (indices[k] != self) site_distances.push_back(site_distance(site, sites_[indices[k]]));
    // Every site not fetched is at least the farthest fetched Euclidean distance away, and its
    // site distance is at least that: the m-th smallest fetched is final when within it.
    const double farthest = found > 0 ? std::sqrt(distances_squared[found - 1]) : 0;
    if (site_distances.size() >= m) {
      std::nth_element(site_distances.begin(), site_distances.begin() + static_cast<std::ptrdiff_t>(m - 1),
                       site_distances.end());
      const double mth = site_distances[m - 1];
      if (mth <= farthest || found == sites_.size()) return mth;
    }
    if (found == sites_.size()) return std::numeric_limits<double>::infinity();
  }
}

}  // namespace candela
