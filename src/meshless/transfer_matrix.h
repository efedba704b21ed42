// The transfer operator of the meshless method (seed 002 §5.2, SPEC §11), stored sparse:
//
//   R = Q S,  Q = diag(β(ṗ_j)) per channel,  S_jk = ∫ φ_k(q) G(q, ṗ_j) V(q, ṗ_j) dq            (5.6, 5.7)
//   G(q, p_j) = max(0, v·q⃗) max(0, −v·p⃗_j) / (π d²),  v from q to p_j, d = |ṗ_j − q|
//
// which for a partition of unity adds up, over k, to the share of p_j's hemisphere that sees the
// elements' surfaces: 1 in a closed room (000 eq. 6-6). The thesis takes the kernel at the centre,
// S_jk ≈ F(p_k, p_j) A_k (eq. 5.2) with A_k the element's effective area; that is good far away
// and wrong close by (rows of a closed box summed to 0.91 along its edges and 0.985–0.99
// elsewhere, a furnace at ρ = 0.9 came out 13 % dark, and a row could pass 1 across a corner,
// where eq. 5.2 grows without bound). So each row is made of two parts:
//   - the near field, the elements with |ṗ_k − ṗ_j| < near_field · r_k (and the receiver's own):
//     the integral itself, by `gather_rays` stratified cosine-distributed rays from p_j — a ray
//     that hits q adds φ_k(q)/N to S_jk, so the hit's share of the hemisphere is split among the
//     elements covering q exactly as the basis splits the surface there;
//   - the far field: eq. 5.2 with a shadow ray between the sites for its shape (smooth and
//     noiseless where the elements are small as seen from p_j), scaled so that it adds up to what
//     the same rays found of the far elements (Σ over hits of the far φ_k(q), over N).
// A row then sums to the rays' share that hit covered surface, which is 1 in a closed room
// whatever the spacing; the rays are seeded per receiver, so S does not depend on threads or ranks.
//
// Hierarchical transport (Lehtinen et al. 2008, after hierarchical radiosity, Hanrahan,
// Salzman and Aupperle 1991): given a site hierarchy (meshless/site_hierarchy.h), the far field is
// carried by links between nodes of the hierarchy — a node standing for its subtree of sites with
// their total effective area, area-weighted centroid and mean normal and, as a sender, their
// area-weighted mean radiosity. A refinement oracle starts from every pair of top-level nodes and
// links a pair (receiver, sender) when
//   - both are small for their distance: each one's extent about its centroid under cluster_angle
//     × the distance between them (the transfer's error grows with the nodes' angular size), and
//     neither one's normals spread by more than about 25°;
//   - no site of the sender is a near element of a site of the receiver (those are integrated);
//   - shadow rays between up to four of their largest children agree (partial visibility is refined);
// otherwise it splits the larger of the two; a pair of sites is linked as the flat matrix links
// them. A site gathers through its own links and those of its coarser ancestors (pushed down the
// tree), the whole far field scaled to the rays' total as the flat rows are, so that what a site
// gathers from a radiosity of 1 is still the covered share of its hemisphere (1 in a closed room).
// S holds the near entries and the sites' own links (scaled), in n rows and as many columns as the
// hierarchy has nodes; receiver_links the clusters' links. The links grow as O(n log n) at worst
// and about as n where the oracle can close pairs at every level; with cluster_angle = 0 every pair
// is refined down to sites and S is the flat matrix, entry for entry.
//
// The solution (002 §5.2.4): λ ← η + Q S λ, per channel, from λ = η, until no coefficient changes by
// more than tolerance × the largest; λ are the coefficients of the radiosity (exitance) in the
// basis, η those of what is emitted and directly reflected.
#pragma once

#include <Eigen/SparseCore>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "math/vector.h"
#include "meshless/site.h"

namespace candela {

class Cluster;
class MeshlessBasis;
class ProgressReporter;
class Scene;
class SiteHierarchy;
struct SiteSet;

struct TransferSettings {
  int gather_rays = 256;        // N: per receiver, for the near field and the far field's total
  double near_field = 2;        // elements closer than this many of their radii are integrated
  uint64_t seed = 0;            // the rays' streams: one per (seed, receiver)
  std::size_t max_entries = 0;  // refused past this (0: no limit)
  double cluster_angle = 0.15;  // hierarchical transport: nodes are linked while extent/distance < this
};

struct TransferMatrix {
  // n × n, or n × (nodes of the hierarchy) for hierarchical transport
  Eigen::SparseMatrix<float, Eigen::RowMajor, int32_t> S;
  // Hierarchical transport: column n + c is cluster c, whose radiosity is Σ weight × its
  // children's (site columns or earlier clusters), the terms of cluster c in
  // cluster_terms[cluster_start[c], cluster_start[c + 1]). Empty for the flat matrix.
  std::vector<uint32_t> cluster_start;
  std::vector<std::pair<int32_t, float>> cluster_terms;
  // Links whose receiver is a cluster: row c − n for node c (n rows fewer than columns), unscaled;
  // a site gets its ancestors' gathered light times push_scale (its far-field scale); parent: the
  // hierarchy's tree (UINT32_MAX at the top).
  Eigen::SparseMatrix<float, Eigen::RowMajor, int32_t> receiver_links;
  std::vector<double> push_scale;
  std::vector<uint32_t> parent;
  std::size_t cluster_links = 0;  // links with a cluster at either end
  std::size_t entries() const { return static_cast<std::size_t>(S.nonZeros() + receiver_links.nonZeros()); }
  double density() const;     // entries / n²
  std::size_t bytes() const;  // values, column indices, row offsets and cluster terms
  // The radiosity of every column's sender from the sites' λ: λ itself for the sites, then each
  // cluster's area-weighted mean of its children's.
  void sender_values(const std::vector<Color>& lambda, std::vector<Color>& senders) const;
  // Per site (the first n), what the links of its coarser ancestors gather from `senders` (one per
  // column), scaled by its far-field scale; empty-handed for the flat matrix.
  void pushed_values(const std::vector<Color>& senders, std::vector<Color>& pushed) const;
  double seconds = 0;            // to compute
  uint64_t visibility_rays = 0;  // shadow rays between sites
  uint64_t gather_rays = 0;      // the rows' hemisphere rays
  // Σ over rows of (the far field's total by the rays) / (its total by eq. 5.2), over the rows
  // that have both: how far eq. 5.2 is from the integral on this scene (1 where it is exact).
  double far_field_scale = 1;
};

// S for the sites (positions, normals, the objects and sides they lie on), their basis (which
// refers to the same sites) and their effective areas A_k; the scene's accelerator traces the rays.
// With a hierarchy over the same sites, the hierarchical transport described above.
// Rows in parallel, each by one thread into its own place: the result does not depend on the
// thread count. settings.max_entries refuses (std::invalid_argument naming the spacing) before
// more would be kept. With a cluster of several ranks the rows are computed across them and every
// rank gets all of S, the same as one process computes. progress, when given, is
// advanced once per row (rank 0 counts every rank's rows). Throws std::invalid_argument for
// mismatched sizes, gather_rays < 1 or near_field < 0.
TransferMatrix compute_transfer_matrix(const Scene& scene, const SiteSet& sites, const MeshlessBasis& basis,
                                       const std::vector<double>& effective_area,
                                       const TransferSettings& settings = {}, Cluster* cluster = nullptr,
                                       ProgressReporter* progress = nullptr,
                                       const SiteHierarchy* hierarchy = nullptr);

struct TransferSolution {
  std::vector<Color> lambda;
  std::size_t iterations = 0;
  bool converged = false;
  bool diverged = false;    // λ grew past 10¹² × max η or overflowed: the iteration stopped
  double final_change = 0;  // the last iteration's largest change over the largest λ
};

// Called after every iteration (1-based) with λ then (the convergence log).
using TransferIterationCallback =
    std::function<void(std::size_t iteration, const std::vector<Color>& lambda)>;

// λ = η + Q S λ by the iteration of 002 §5.2.4 (Q = albedo); progress, when given, advances in
// per mille of convergence (the change's way down to the tolerance, on a log scale). Throws
// std::invalid_argument for mismatched sizes.
TransferSolution solve_transfer(const TransferMatrix& transfer, const std::vector<Color>& albedo,
                                const std::vector<Color>& eta, double tolerance, std::size_t max_iterations,
                                ProgressReporter* progress = nullptr,
                                const TransferIterationCallback& on_iteration = {});

}  // namespace candela
