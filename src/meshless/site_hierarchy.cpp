#include "meshless/site_hierarchy.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "math/bounds.h"
#include "meshless/site_index.h"
#include "meshless/site_sampling.h"
#include "meshless/spacing_filter.h"

namespace candela {

struct SiteHierarchy::Level {
  std::vector<uint32_t> members;  // indices into the set
  std::vector<Site> sites;        // the members' sites, in the same order
  std::vector<double> radius;
  double spacing = 0;
  std::unique_ptr<MeshlessBasis> basis;  // normalized, over sites and radius
};

SiteHierarchy::SiteHierarchy(const SiteSet& set, int neighbours, std::size_t coarsest_sites) : set_(&set) {
  if (!(set.spacing > 0) || !std::isfinite(set.spacing))
    throw std::invalid_argument("site hierarchy: the sites' spacing must be finite and > 0");
  if (neighbours < 1) throw std::invalid_argument("site hierarchy: neighbours must be >= 1");
  if (coarsest_sites < 1) throw std::invalid_argument("site hierarchy: coarsest_sites must be >= 1");
  if (set.radius.size() != set.sites.size())
    throw std::invalid_argument("site hierarchy: " + std::to_string(set.radius.size()) + " radii for " +
                                std::to_string(set.sites.size()) + " sites");
  const std::size_t n = set.sites.size();
  auto finest = std::make_unique<Level>();
  finest->members.resize(n);
  for (uint32_t i = 0; i < n; ++i) finest->members[i] = i;
  finest->sites = set.sites;
  finest->radius = set.radius;
  finest->spacing = set.spacing;
  levels_.push_back(std::move(finest));
  // Poisson-disc thinning, the spacing doubling per level, until a level is small. A spacing that
  // thins nothing (objects farther apart than it) doubles again without making a level; once it
  // passes the sites' extent, only normals 90° or more apart keep sites apart and thinning ends.
  Bounds3 extent;
  for (const Site& site : set.sites) extent.extend(site.position);
  const double diameter = set.sites.empty() ? 0.0 : length(extent.diagonal());
  double spacing = set.spacing;
  while (levels_.back()->members.size() > coarsest_sites && spacing <= 2 * diameter) {
    const Level& finer = *levels_.back();
    auto coarser = std::make_unique<Level>();
    spacing *= 2;
    coarser->spacing = spacing;
    SpacingFilter filter(coarser->spacing);
    for (std::size_t i = 0; i < finer.members.size(); ++i)
      if (filter.try_keep(finer.sites[i])) {
        coarser->members.push_back(finer.members[i]);
        coarser->sites.push_back(finer.sites[i]);
      }
    if (coarser->members.size() == finer.members.size()) continue;
    // 002 §4.2.7 within the level: the site distance holding its m nearest sites of that level.
    const SiteIndex index(coarser->sites);
    coarser->radius.resize(coarser->sites.size());
    tbb::parallel_for(std::size_t(0), coarser->sites.size(), [&](std::size_t i) {
      coarser->radius[i] = index.mth_nearest_site_distance(
          coarser->sites[i], static_cast<std::size_t>(neighbours), static_cast<uint32_t>(i));
    });
    levels_.push_back(std::move(coarser));
  }
  for (auto& level : levels_)
    level->basis = std::make_unique<MeshlessBasis>(level->sites, level->radius, BasisKind::normalized);

  // Nodes level by level; each node's parent is the nearest site of the next level.
  for (std::size_t l = 0; l < levels_.size(); ++l) {
    level_offset_.push_back(static_cast<uint32_t>(node_site_.size()));
    for (const uint32_t site : levels_[l]->members) {
      node_site_.push_back(site);
      node_level_.push_back(static_cast<uint32_t>(l));
    }
  }
  parent_.assign(node_site_.size(), UINT32_MAX);
  std::vector<uint32_t> member_on_next(n, UINT32_MAX);
  for (std::size_t l = 0; l + 1 < levels_.size(); ++l) {
    const Level& level = *levels_[l];
    const Level& next = *levels_[l + 1];
    std::fill(member_on_next.begin(), member_on_next.end(), UINT32_MAX);
    for (uint32_t i = 0; i < next.members.size(); ++i) member_on_next[next.members[i]] = i;
    const SiteIndex index(next.sites);
    tbb::parallel_for(std::size_t(0), level.members.size(), [&](std::size_t i) {
      uint32_t chosen = member_on_next[level.members[i]];
      if (chosen == UINT32_MAX) {
        // A site thinned away had a kept one within the next level's spacing (site distance,
        // hence Euclidean too); the search widens in case rounding put it just outside.
        thread_local std::vector<uint32_t> candidates;
        double best = std::numeric_limits<double>::infinity(), best_gap = best;
        for (double reach = next.spacing; chosen == UINT32_MAX || reach <= next.spacing; reach *= 2) {
          candidates.clear();
          index.within_euclidean(level.sites[i].position, reach, candidates);
          for (const uint32_t c : candidates) {
            const double d = site_distance(level.sites[i], next.sites[c]);
            const double gap = length(level.sites[i].position - next.sites[c].position);
            // The nearest by site distance; where every normal faces away, the nearest in space.
            if (d < best || (d == best && (gap < best_gap || (gap == best_gap && c < chosen)))) {
              best = d, best_gap = gap, chosen = c;
            }
          }
          if (candidates.size() == next.sites.size()) break;
        }
      }
      parent_[level_offset_[l] + i] = level_offset_[l + 1] + chosen;
    });
  }
  // Children by counting, each list in increasing node order.
  child_start_.assign(node_site_.size() + 1, 0);
  for (const uint32_t p : parent_)
    if (p != UINT32_MAX) ++child_start_[p + 1];
  for (std::size_t c = 0; c < node_site_.size(); ++c) child_start_[c + 1] += child_start_[c];
  child_list_.resize(child_start_.back());
  std::vector<uint32_t> filled(child_start_.begin(), child_start_.end() - 1);
  for (uint32_t c = 0; c < parent_.size(); ++c)
    if (parent_[c] != UINT32_MAX) child_list_[filled[parent_[c]]++] = c;
}

SiteHierarchy::~SiteHierarchy() = default;
SiteHierarchy::SiteHierarchy(SiteHierarchy&&) noexcept = default;
SiteHierarchy& SiteHierarchy::operator=(SiteHierarchy&&) noexcept = default;

std::span<const uint32_t> SiteHierarchy::level_sites(std::size_t level) const {
  return levels_.at(level)->members;
}
std::span<const double> SiteHierarchy::level_radii(std::size_t level) const {
  return levels_.at(level)->radius;
}
const MeshlessBasis& SiteHierarchy::level_basis(std::size_t level) const {
  return *levels_.at(level)->basis;
}
double SiteHierarchy::level_spacing(std::size_t level) const {
  return levels_.at(level)->spacing;
}

std::span<const uint32_t> SiteHierarchy::children(uint32_t node) const {
  return std::span<const uint32_t>(child_list_)
      .subspan(child_start_[node], child_start_[node + 1] - child_start_[node]);
}

void SiteHierarchy::evaluate(const Site& p, std::vector<std::pair<uint32_t, double>>& weights) const {
  weights.clear();
  thread_local std::vector<std::pair<uint32_t, double>> level_weights;
  for (std::size_t l = 0; l < levels_.size(); ++l) {
    levels_[l]->basis->evaluate(p, level_weights);
    for (const auto& [member, value] : level_weights) weights.emplace_back(level_offset_[l] + member, value);
  }
}

Color SiteHierarchy::reconstruct(const Site& p, std::span<const Color> coefficients) const {
  if (coefficients.size() != node_count())
    throw std::invalid_argument("site hierarchy: " + std::to_string(coefficients.size()) +
                                " coefficients for " + std::to_string(node_count()) + " nodes");
  thread_local std::vector<std::pair<uint32_t, double>> weights;
  evaluate(p, weights);
  Color total;
  for (const auto& [node, value] : weights) total += coefficients[node] * value;
  return total;
}

std::vector<Color> SiteHierarchy::project(std::span<const Color> values) const {
  const std::size_t n = set_->sites.size();
  if (values.size() != n)
    throw std::invalid_argument("site hierarchy: " + std::to_string(values.size()) + " values for " +
                                std::to_string(n) + " sites");
  std::vector<Color> coefficients(node_count());
  std::vector<Color> coarser(n);  // Σ over the levels done so far, at every site
  for (std::size_t l = levels_.size(); l-- > 0;) {
    const Level& level = *levels_[l];
    for (std::size_t i = 0; i < level.members.size(); ++i)
      coefficients[level_offset_[l] + i] = values[level.members[i]] - coarser[level.members[i]];
    if (l == 0) break;
    tbb::parallel_for(std::size_t(0), n, [&](std::size_t j) {
      thread_local std::vector<std::pair<uint32_t, double>> weights;
      level.basis->evaluate(set_->sites[j], weights);
      for (const auto& [member, value] : weights)
        coarser[j] += coefficients[level_offset_[l] + member] * value;
    });
  }
  return coefficients;
}

}  // namespace candela
