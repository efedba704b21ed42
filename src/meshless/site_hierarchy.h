// The hierarchical meshless basis (Lehtinen, Zwicker, Turquin, Kontkanen, Durand, Sillion
// and Aila, "A Meshless Hierarchical Representation for Light Transport", SIGGRAPH 2008, §4 — the
// paper seed 002 follows in its flat form).
//
// Levels of decreasing density over the sites of a SiteSet:
//   - level 0 is every site, in the set's order, with the set's radii;
//   - level l + 1 is a subset of level l, thinned as a Poisson-disc set with twice the spacing:
//     level l's sites are offered in their order and kept unless a kept one lies within
//     2^(l+1)·Δ (site distance), so the levels nest and each is about a quarter as dense on a
//     surface; a spacing that thins nothing (objects farther apart than it) doubles again without
//     making a level; thinning stops at a level of at most `coarsest_sites` sites, or once the
//     spacing passes twice the sites' extent (then only normals 90° or more apart keep sites
//     apart);
//   - each level has its own radii (the site distance holding its m nearest sites of the same
//     level, 002 §4.2.7) and its own normalized radial basis φ^l_i (002 eq. 4.9), a partition of
//     unity over the surfaces its sites cover.
// The hierarchical functions are the union of every level's φ^l_i; a function of the surfaces is
// L(p) = Σ_l Σ_i c^l_i φ^l_i(p). `project` finds coefficients from values at the sites as a
// multilevel scattered-data approximation does (Floater and Iske 1996): the coarsest level takes
// the values at its sites, each finer level the residual at its sites of what the coarser levels
// already give, so that a smooth function lives in few coarse coefficients and the fine levels
// hold its details (near zero where it is smooth — what makes the representation compressible).
// With every coefficient on level 0 the evaluation is the flat normalized basis's.
//
// The tree: every site of level l < top has a parent on level l + 1, the nearest there by site
// distance (a site that is on level l + 1 is its own parent). Nodes are numbered level by level,
// level 0 first, so node i < n is site i, and a node's children always come before it. The
// hierarchical transport (meshless/transfer_matrix.h) gathers the light of a node's subtree as one
// cluster where the refinement oracle allows it.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <utility>
#include <vector>

#include "math/vector.h"
#include "meshless/meshless_basis.h"
#include "meshless/site.h"

namespace candela {

struct SiteSet;

class SiteHierarchy {
 public:
  // The levels over set.sites (its radii for level 0) with spacing Δ = set.spacing (> 0) and m =
  // neighbours. The set must outlive the hierarchy. Throws std::invalid_argument for Δ ≤ 0,
  // neighbours < 1 or coarsest_sites < 1.
  SiteHierarchy(const SiteSet& set, int neighbours, std::size_t coarsest_sites = 16);
  ~SiteHierarchy();
  SiteHierarchy(SiteHierarchy&&) noexcept;
  SiteHierarchy& operator=(SiteHierarchy&&) noexcept;

  std::size_t level_count() const { return levels_.size(); }
  // Level l's sites, as indices into the set (increasing: each level keeps its finer level's order).
  std::span<const uint32_t> level_sites(std::size_t level) const;
  std::span<const double> level_radii(std::size_t level) const;
  const MeshlessBasis& level_basis(std::size_t level) const;
  double level_spacing(std::size_t level) const;

  // The tree (see the header). node_count() = Σ_l level size.
  std::size_t node_count() const { return node_site_.size(); }
  uint32_t node(std::size_t level, std::size_t member) const {
    return level_offset_[level] + uint32_t(member);
  }
  uint32_t node_site(uint32_t node) const { return node_site_[node]; }
  uint32_t node_level(uint32_t node) const { return node_level_[node]; }
  uint32_t parent(uint32_t node) const { return parent_[node]; }  // UINT32_MAX on the top level
  std::span<const uint32_t> children(uint32_t node) const;        // empty for level 0

  // Every non-zero φ^l_i(p) over all levels, as (node, value) pairs, level by level (each level's
  // as its basis gives them: increasing, then its elements of unbounded support).
  void evaluate(const Site& p, std::vector<std::pair<uint32_t, double>>& weights) const;
  // L(p) from one coefficient per node.
  Color reconstruct(const Site& p, std::span<const Color> coefficients) const;
  // The multilevel coefficients (one per node) of the values at the set's sites (one per site).
  std::vector<Color> project(std::span<const Color> values) const;

 private:
  struct Level;
  const SiteSet* set_;
  std::vector<std::unique_ptr<Level>> levels_;  // each level stays where it is: its basis refers to it
  std::vector<uint32_t> level_offset_;          // the first node of each level
  std::vector<uint32_t> node_site_, node_level_, parent_;
  std::vector<uint32_t> child_start_, child_list_;  // children of node c: child_list_[start[c], start[c+1])
};

}  // namespace candela
