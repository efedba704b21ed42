#include "meshless/transfer_matrix.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "distributed/cluster.h"
#include "distributed/task_farm.h"
#include "math/constants.h"
#include "math/pcg32.h"
#include "meshless/meshless_basis.h"
#include "meshless/site_hierarchy.h"
#include "meshless/site_index.h"
#include "meshless/site_sampling.h"
#include "sampling/warps.h"
#include "scene/scene.h"
#include "util/progress.h"

namespace candela {

double TransferMatrix::density() const {
  const double n = static_cast<double>(S.rows());
  return n > 0 ? static_cast<double>(entries()) / (n * n) : 0.0;
}

std::size_t TransferMatrix::bytes() const {
  return static_cast<std::size_t>(S.nonZeros() + receiver_links.nonZeros()) *
             (sizeof(float) + sizeof(int32_t)) +
         static_cast<std::size_t>(S.rows() + receiver_links.rows() + 2) * sizeof(int32_t) +
         push_scale.size() * sizeof(double) + parent.size() * sizeof(uint32_t) +
         cluster_start.size() * sizeof(uint32_t) + cluster_terms.size() * sizeof(cluster_terms[0]);
}

void TransferMatrix::sender_values(const std::vector<Color>& lambda, std::vector<Color>& senders) const {
  senders.assign(static_cast<std::size_t>(S.cols()), Color());
  std::copy(lambda.begin(), lambda.end(), senders.begin());
  const std::size_t n = lambda.size();
  // Children before parents: one pass in column order.
  for (std::size_t c = 0; c + 1 < cluster_start.size(); ++c) {
    Color mean;
    for (uint32_t t = cluster_start[c]; t < cluster_start[c + 1]; ++t)
      mean += senders[static_cast<std::size_t>(cluster_terms[t].first)] *
              static_cast<double>(cluster_terms[t].second);
    senders[n + c] = mean;
  }
}

namespace {

// One entry of a row of S: a flat pair, so rows cross between ranks as arrays.
struct Entry {
  int32_t column;
  float value;
};
using Row = std::vector<Entry>;

// V: a shadow ray from one site toward another, both ends off their surfaces.
bool sites_see_each_other(const Scene& scene, const Site& from, const Site& to) {
  Ray ray;
  ray.origin = from.position + from.normal * scene.ray_offset(from.position);
  const Vec3 target = to.position + to.normal * scene.ray_offset(to.position);
  const Vec3 to_target = target - ray.origin;
  const double distance = length(to_target);
  if (!(distance > 0)) return false;
  ray.direction = to_target / distance;
  ray.t_max = distance * (1 - 1e-9);
  return !scene.occluded(ray);
}

// 002 eq. 5.2 × A: the transfer to a receiver at `receiver` facing `receiver_normal` (unit) from a
// sender at `sender` whose area-weighted normal sum is `area_normal` (A_k p⃗_k for one site); 0
// when either faces away.
double point_transfer(const Vec3& receiver, const Vec3& receiver_normal, const Vec3& sender,
                      const Vec3& area_normal) {
  const Vec3 between = receiver - sender;  // v_kj · d
  const double d2 = dot(between, between);
  if (!(d2 > 0)) return 0.0;
  const double d = std::sqrt(d2);
  const Vec3 v = between / d;
  const double cos_sender_area = dot(v, area_normal), cos_receiver = -dot(v, receiver_normal);
  if (!(cos_sender_area > 0) || !(cos_receiver > 0)) return 0.0;
  return cos_sender_area * cos_receiver / (kPi * d2);
}

// One link of the hierarchical transport: what receiver node gathers from sender node per unit of
// the sender's radiosity (unscaled: before the receiver's far field is scaled to its rays).
struct Link {
  uint32_t receiver, sender;
  double transfer;
  bool operator<(const Link& other) const {
    return receiver != other.receiver ? receiver < other.receiver : sender < other.sender;
  }
};

// The hierarchy's nodes as senders: per node its sites' total effective area, their
// area-weighted centroid and Σ A·normal, how far its sites lie from the centroid, the farthest any
// of them counts a receiver as near (near_field × its radius), and up to four of its children's
// sites (the largest) for the visibility oracle.
struct SenderClusters {
  std::vector<double> area, extent, near_reach;
  std::vector<double> cone;  // the least cosine between a site's normal and the node's mean normal
  std::vector<Vec3> centroid, area_normal;
  std::vector<Vec3> mean_normal;                 // unit (a site's own normal); 0 for a cluster without area
  std::vector<std::array<uint32_t, 4>> samples;  // site indices, UINT32_MAX past the last
};

SenderClusters sender_clusters(const SiteHierarchy& hierarchy, const SiteSet& site_set,
                               const std::vector<double>& effective_area, double near_field) {
  const std::size_t nodes = hierarchy.node_count(), n = site_set.sites.size();
  SenderClusters c;
  c.area.assign(nodes, 0);
  c.extent.assign(nodes, 0);
  c.near_reach.assign(nodes, 0);
  c.centroid.assign(nodes, Vec3());
  c.area_normal.assign(nodes, Vec3());
  c.samples.assign(nodes, {UINT32_MAX, UINT32_MAX, UINT32_MAX, UINT32_MAX});
  for (uint32_t node = 0; node < nodes; ++node) {  // children before parents
    if (node < n) {
      const double a = std::max(0.0, effective_area[node]);
      c.area[node] = a;
      c.centroid[node] = site_set.sites[node].position;
      c.area_normal[node] = site_set.sites[node].normal * a;
      // Infinite for an unbounded element (even with near_field 0: it is always a near element).
      c.near_reach[node] = std::isfinite(site_set.radius[node]) ? near_field * site_set.radius[node]
                                                                : std::numeric_limits<double>::infinity();
      c.samples[node][0] = node;
      continue;
    }
    const std::span<const uint32_t> children = hierarchy.children(node);
    Vec3 weighted;
    std::vector<std::pair<double, uint32_t>> by_area;
    for (const uint32_t child : children) {
      c.area[node] += c.area[child];
      weighted += c.centroid[child] * c.area[child];
      c.area_normal[node] += c.area_normal[child];
      c.near_reach[node] = std::max(c.near_reach[node], c.near_reach[child]);
      by_area.emplace_back(-c.area[child], hierarchy.node_site(child));
    }
    c.centroid[node] =
        c.area[node] > 0 ? weighted / c.area[node] : site_set.sites[hierarchy.node_site(node)].position;
    std::sort(by_area.begin(), by_area.end());
    for (std::size_t k = 0; k < std::min<std::size_t>(4, by_area.size()); ++k)
      c.samples[node][k] = by_area[k].second;
  }
  // The extent and the normals' spread: every site against each of its ancestors.
  c.cone.assign(nodes, 1.0);
  c.mean_normal.assign(nodes, Vec3());
  for (uint32_t node = 0; node < nodes; ++node) {
    const double norm = length(c.area_normal[node]);
    if (node < n)
      c.mean_normal[node] = site_set.sites[node].normal;
    else if (norm > 0)
      c.mean_normal[node] = c.area_normal[node] / norm;
    else
      c.cone[node] = -1;  // no direction: never linked as a cluster
  }
  for (uint32_t site = 0; site < n; ++site)
    for (uint32_t node = hierarchy.parent(site); node != UINT32_MAX; node = hierarchy.parent(node)) {
      c.extent[node] = std::max(c.extent[node], length(site_set.sites[site].position - c.centroid[node]));
      c.cone[node] = std::min(c.cone[node], dot(site_set.sites[site].normal, c.mean_normal[node]));
    }
  return c;
}

// The arguments' sizes and ranges, refused before any work.
void check_transfer_inputs(const SiteSet& site_set, const std::vector<double>& effective_area,
                           const TransferSettings& settings, const SiteHierarchy* hierarchy) {
  const std::vector<Site>& sites = site_set.sites;
  if (effective_area.size() != sites.size())
    throw std::invalid_argument("transfer matrix: " + std::to_string(effective_area.size()) + " areas for " +
                                std::to_string(sites.size()) + " sites");
  if (site_set.radius.size() != sites.size())
    throw std::invalid_argument("transfer matrix: " + std::to_string(site_set.radius.size()) + " radii for " +
                                std::to_string(sites.size()) + " sites");
  if (settings.gather_rays < 1) throw std::invalid_argument("transfer matrix: gather_rays must be >= 1");
  if (!(settings.near_field >= 0)) throw std::invalid_argument("transfer matrix: near_field must be >= 0");
  if (!(settings.cluster_angle >= 0))
    throw std::invalid_argument("transfer matrix: cluster_angle must be >= 0");
  if (hierarchy && hierarchy->node_count() < sites.size())
    throw std::invalid_argument("transfer matrix: the hierarchy is not over these sites");
}

// The links of the hierarchical transport, sorted by receiver then sender.
struct HierarchicalLinks {
  std::vector<Link> links;
  std::vector<std::size_t> link_start;  // per node, where its links as a receiver start; one more at the end
  std::vector<double> from_ancestors;   // per site: Σ transfer of its ancestors' links
  uint64_t rays = 0;                    // the shadow rays the refinement traced
};

// The refinement of the hierarchical transport from one pair of nodes down.
struct LinkRefinement {
  const Scene& scene;
  const SiteSet& site_set;
  const SiteHierarchy& hierarchy;
  const SenderClusters& clusters;
  const TransferSettings& settings;
  std::size_t n;  // sites

  // A cluster is linked whole only when every one of its sites' normals lies within about 25° of
  // its mean (cos 25° = 0.906).
  bool closable(uint32_t node) const {
    return node < n ||
           (hierarchy.children(node).size() > 1 && clusters.area[node] > 0 && clusters.cone[node] >= 0.906);
  }

  // Two sites: the flat matrix's far entry, unless the sender is a near element.
  void link_sites(uint32_t receiver, uint32_t sender, std::vector<Link>& out, uint64_t& rays) const {
    const std::vector<Site>& sites = site_set.sites;
    // The near test of RowGatherer::find_near_elements, to the bit.
    const double r = site_set.radius[sender], reach = settings.near_field * r;
    const double d2 = length_squared(sites[sender].position - sites[receiver].position);
    if (receiver == sender || !std::isfinite(r) || d2 < reach * reach) return;
    const double transfer = point_transfer(sites[receiver].position, sites[receiver].normal,
                                           sites[sender].position, clusters.area_normal[sender]);
    if (!(transfer > 0)) return;
    ++rays;
    if (sites_see_each_other(scene, sites[receiver], sites[sender]))
      out.push_back({receiver, sender, transfer});
  }

  // Whether the pair is settled whole (linked, hidden, or facing away); false when it is to be split.
  bool settle_pair(uint32_t receiver, uint32_t sender, std::vector<Link>& out, uint64_t& rays) const {
    const std::vector<Site>& sites = site_set.sites;
    const double angle = settings.cluster_angle;
    const double d = length(clusters.centroid[receiver] - clusters.centroid[sender]);
    const double receiver_extent = clusters.extent[receiver], sender_extent = clusters.extent[sender];
    if (closable(receiver) && closable(sender) &&
        d > receiver_extent + sender_extent + clusters.near_reach[sender] && receiver_extent < angle * d &&
        sender_extent < angle * d) {
      const double transfer = point_transfer(clusters.centroid[receiver], clusters.mean_normal[receiver],
                                             clusters.centroid[sender], clusters.area_normal[sender]);
      if (!(transfer > 0)) return true;  // facing away, or below the receiver's horizon
      const auto& from = clusters.samples[receiver];
      const auto& to = clusters.samples[sender];
      const auto count = [](const std::array<uint32_t, 4>& samples) {
        return static_cast<int>(std::find(samples.begin(), samples.end(), UINT32_MAX) - samples.begin());
      };
      const int from_count = count(from), to_count = count(to), tried = std::max(from_count, to_count);
      int seen = 0;
      for (int i = 0; i < tried; ++i)
        seen += sites_see_each_other(scene, sites[from[static_cast<std::size_t>(i % from_count)]],
                                     sites[to[static_cast<std::size_t>(i % to_count)]]);
      rays += static_cast<uint64_t>(tried);
      if (seen == 0) return true;  // hidden
      if (seen == tried) {
        out.push_back({receiver, sender, transfer});
        return true;
      }
      // Partly hidden: refined.
    }
    return false;
  }

  // Every pair (receiver_root, top-level node) refined down into out, the rays traced added to
  // rays; found_count counts the links of every task, in steps of 1024.
  void refine(uint32_t receiver_root, const std::vector<uint32_t>& roots, std::vector<Link>& out,
              uint64_t& rays, std::atomic<std::size_t>& found_count, std::atomic<bool>& too_many) const {
    const std::size_t max_entries = settings.max_entries;
    std::vector<std::pair<uint32_t, uint32_t>> open;
    for (auto root = roots.rbegin(); root != roots.rend(); ++root) open.emplace_back(receiver_root, *root);
    std::size_t counted = 0;  // of out's links, those added to found_count
    while (!open.empty()) {
      if (out.size() >= counted + 1024) {
        counted += 1024;
        if (max_entries > 0 && (found_count += 1024) > max_entries) too_many = true;
      }
      if (too_many.load(std::memory_order_relaxed)) break;
      const auto [receiver, sender] = open.back();
      open.pop_back();
      if (!(clusters.area[sender] > 0)) continue;
      if (receiver < n && sender < n) {
        link_sites(receiver, sender, out, rays);
        continue;
      }
      if (settle_pair(receiver, sender, out, rays)) continue;
      // Split the larger (a site cannot be split).
      const double receiver_extent = clusters.extent[receiver], sender_extent = clusters.extent[sender];
      const bool split_sender = receiver < n || (sender >= n && sender_extent >= receiver_extent);
      if (split_sender) {
        const auto children = hierarchy.children(sender);
        for (auto child = children.rbegin(); child != children.rend(); ++child)
          open.emplace_back(receiver, *child);
      } else {
        const auto children = hierarchy.children(receiver);
        for (auto child = children.rbegin(); child != children.rend(); ++child)
          open.emplace_back(*child, sender);
      }
    }
  }
};

// The links found from each top-level receiver in one sorted list, where each node's links start,
// and per site what its coarser ancestors' links bring.
HierarchicalLinks merge_links(std::vector<std::vector<Link>>& found, const std::vector<uint64_t>& found_rays,
                              std::size_t total_links, const SiteHierarchy& hierarchy, std::size_t n) {
  const std::size_t columns = hierarchy.node_count();
  HierarchicalLinks merged;
  std::vector<Link>& links = merged.links;
  std::vector<std::size_t>& link_start = merged.link_start;
  links.reserve(total_links);
  for (auto& list : found) {
    links.insert(links.end(), list.begin(), list.end());
    std::vector<Link>().swap(list);
  }
  std::sort(links.begin(), links.end());
  for (const uint64_t r : found_rays) merged.rays += r;
  link_start.assign(columns + 1, 0);
  for (const Link& link : links) ++link_start[link.receiver + 1];
  for (std::size_t c = 0; c < columns; ++c) link_start[c + 1] += link_start[c];
  // Per node the transfer of its links, then per site the sum over its coarser ancestors.
  std::vector<double> own(columns, 0.0), above(columns, 0.0);
  for (std::size_t c = 0; c < columns; ++c)
    for (std::size_t l = link_start[c]; l < link_start[c + 1]; ++l) own[c] += links[l].transfer;
  for (std::size_t c = columns; c-- > 0;) {  // parents before children
    const uint32_t parent = hierarchy.parent(static_cast<uint32_t>(c));
    above[c] = parent == UINT32_MAX ? 0.0 : above[parent] + own[parent];
  }
  merged.from_ancestors.assign(above.begin(), above.begin() + static_cast<std::ptrdiff_t>(n));
  return merged;
}

// The links of the hierarchical transport, refining pairs of nodes from every pair of
// top-level nodes down (hierarchical radiosity's refinement, Hanrahan, Salzman and Aupperle 1991):
// a pair is linked while both nodes are small for their distance (cluster_angle), their normals
// agree, no site of the sender is a near element of a site of the receiver, and up to four shadow
// rays between their largest children agree; otherwise the larger one is split. A pair of sites
// that are not near each other is linked as the flat matrix would (one shadow ray).
HierarchicalLinks refine_links(const LinkRefinement& refinement, Cluster* cluster) {
  const SiteHierarchy& hierarchy = refinement.hierarchy;
  const std::size_t max_entries = refinement.settings.max_entries;
  std::vector<uint32_t> roots;
  const std::size_t top = hierarchy.level_count() - 1;
  for (std::size_t member = 0; member < hierarchy.level_sites(top).size(); ++member)
    roots.push_back(hierarchy.node(top, member));
  std::atomic<bool> too_many{false};
  std::vector<std::vector<Link>> found(roots.size());  // per top-level receiver
  std::vector<uint64_t> found_rays(found.size(), 0);
  // Past the entry limit every task stops (memory stays bounded) and the matrix is refused below.
  std::atomic<std::size_t> found_count{0};
  tbb::parallel_for(std::size_t(0), found.size(), [&](std::size_t task) {
    refinement.refine(roots[task], roots, found[task], found_rays[task], found_count, too_many);
  });
  std::size_t total_links = 0;
  for (const auto& list : found) total_links += list.size();
  if (max_entries > 0 && total_links > max_entries) too_many = true;
  // Every rank refuses alike (their limits follow each machine's memory): a collective.
  if (cluster && cluster->distributed()) too_many = !cluster->all(!too_many);
  if (too_many)
    throw std::invalid_argument(
        "transfer matrix: more than " + std::to_string(max_entries) +
        " links; raise meshless.spacing (fewer sites) or meshless.cluster_angle (or raise "
        "render.memory_limit_mib: 16 bytes an entry)");
  return merge_links(found, found_rays, total_links, hierarchy, refinement.n);
}

// A thread's scratch space for its rows: the basis's weights at a hit, and the receiver's near
// elements (one flag per site, set for a row and cleared after it) with the k-d tree's candidates.
struct RowScratch {
  std::vector<std::pair<uint32_t, double>> weights;
  std::vector<uint8_t> near;
  std::vector<uint32_t> near_list, candidates;
};

// What each receiver gathers from every site: one row of S.
class RowGatherer {
 public:
  // links: the hierarchical transport's, or null for the flat matrix.
  RowGatherer(const Scene& scene, const SiteSet& site_set, const MeshlessBasis& basis,
              const std::vector<double>& effective_area, const TransferSettings& settings,
              const HierarchicalLinks* links)
      : scene_(scene),
        site_set_(site_set),
        sites_(site_set.sites),
        basis_(basis),
        effective_area_(effective_area),
        settings_(settings),
        links_(links),
        n_(site_set.sites.size()),
        object_sides_(sides_with_sites(site_set, scene.objects.size())),
        // N rays on a √N × √N grid of strata (the rest, when N is no square, unstratified).
        strata_(static_cast<int>(std::sqrt(static_cast<double>(settings.gather_rays)))),
        ray_weight_(1.0 / settings.gather_rays),
        index_(site_set.sites) {
    // The near elements of a receiver are found through a k-d tree: those within near_field × the
    // largest finite radius, and the unbounded ones everywhere.
    for (uint32_t k = 0; k < n_; ++k) {
      if (std::isfinite(site_set.radius[k]))
        largest_radius_ = std::max(largest_radius_, site_set.radius[k]);
      else
        unbounded_.push_back(k);
    }
  }

  // Row j: what receiver j gathers from every site, its far-field scale into far_scales[j] where it
  // has a far field; returns the shadow rays it traced.
  uint64_t compute_row(std::size_t j, Row& row, std::vector<double>& far_scales) const {
    thread_local RowScratch scratch;
    const double near_reach = find_near_elements(j, scratch);
    std::vector<std::pair<int32_t, double>> near_entries;
    const double far_gathered = gather_hemisphere(j, near_reach, scratch, near_entries);
    std::vector<std::pair<int32_t, double>> far_entries;
    const uint64_t row_rays = find_far_entries(j, scratch.near, far_entries);
    // The far field's shape from eq. 5.2, its total from the rays (summed in column order).
    std::sort(far_entries.begin(), far_entries.end());
    double far_sum = 0;
    for (const auto& entry : far_entries) far_sum += entry.second;
    // What the links of the receiver's coarser ancestors bring (per unit radiosity) belongs to
    // its far field too.
    if (links_) far_sum += links_->from_ancestors[j];
    const double scale = far_sum > 0 ? far_gathered / far_sum : 1.0;
    if (far_sum > 0) far_scales[j] = scale;
    for (const auto& [column, transfer] : far_entries)
      row.push_back({column, static_cast<float>(static_cast<float>(transfer) * scale)});
    // The near entries, one per element (added up in ray order), and the row in column order.
    std::stable_sort(near_entries.begin(), near_entries.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    for (std::size_t e = 0; e < near_entries.size();) {
      double total = 0;
      const int32_t column = near_entries[e].first;
      for (; e < near_entries.size() && near_entries[e].first == column; ++e) total += near_entries[e].second;
      row.push_back({column, static_cast<float>(total)});
    }
    for (const uint32_t k : scratch.near_list) scratch.near[k] = 0;
    std::sort(row.begin(), row.end(), [](const Entry& a, const Entry& b) { return a.column < b.column; });
    std::erase_if(row, [](const Entry& entry) { return !(entry.value > 0); });
    return row_rays;
  }

 private:
  // The near elements of receiver j: |ṗ_k − ṗ_j| < near_field · r_k, the receiver's own, and those
  // of unbounded support, flagged in scratch.near and listed in scratch.near_list. Returns how far
  // from p_j they reach: no near element reaches a point farther than that (a support is a ball of
  // radius r_k in Euclidean terms too), so beyond it a hit needs no basis evaluation — most of
  // them, as a site's near elements are mostly on its own plane, where no ray lands.
  double find_near_elements(std::size_t j, RowScratch& scratch) const {
    const Site& receiver = sites_[j];
    std::vector<uint8_t>& near = scratch.near;
    if (near.size() != n_) near.assign(n_, 0);
    scratch.near_list.clear();
    scratch.candidates.clear();
    index_.within_euclidean(receiver.position, settings_.near_field * largest_radius_, scratch.candidates);
    scratch.candidates.insert(scratch.candidates.end(), unbounded_.begin(), unbounded_.end());
    scratch.candidates.push_back(static_cast<uint32_t>(j));
    double near_reach = 0;
    for (const uint32_t k : scratch.candidates) {
      if (near[k]) continue;
      const double r = site_set_.radius[k], d2 = length_squared(sites_[k].position - receiver.position);
      const double reach = settings_.near_field * r;
      if (k == j || !std::isfinite(r) || d2 < reach * reach) {
        near[k] = 1;
        scratch.near_list.push_back(k);
        near_reach = std::max(near_reach, std::sqrt(d2) + r);
      }
    }
    return near_reach;
  }

  // The hemisphere of receiver j: the near elements' integrals into near_entries (one per hit and
  // element), and the far field's total returned.
  double gather_hemisphere(std::size_t j, double near_reach, RowScratch& scratch,
                           std::vector<std::pair<int32_t, double>>& near_entries) const {
    const Site& receiver = sites_[j];
    const Vec3 origin = receiver.position + receiver.normal * scene_.ray_offset(receiver.position);
    double far_gathered = 0;
    Vec3 b1, b2;
    orthonormal_basis(receiver.normal, b1, b2);
    Pcg32 random(settings_.seed ^ 0x6D65736868656D69ull, j);
    for (int s = 0; s < settings_.gather_rays; ++s) {
      Vec2 u{random.next_double(), random.next_double()};
      if (s < strata_ * strata_) u = Vec2{(s % strata_ + u.x) / strata_, (s / strata_ + u.y) / strata_};
      const Vec3 local = square_to_cosine_hemisphere(u);
      Ray ray;
      ray.origin = origin;
      ray.direction = normalize(b1 * local.x + b2 * local.y + receiver.normal * local.z);
      Intersection hit;
      if (!scene_.intersect(ray, hit)) continue;
      const Site q{hit.surface.position, face_forward(hit.surface.geometric_normal, -ray.direction)};
      // Only the sides sites lie on belong to the solution (as in the effective areas).
      const uint32_t object = scene_.primitives[hit.primitive].object;
      const uint8_t side = dot(q.normal, hit.surface.geometric_normal) > 0 ? 1 : 2;
      if (object >= object_sides_.size() || !(object_sides_[object] & side)) continue;
      if (!(length(q.position - receiver.position) < near_reach)) {
        // Far elements only, and they are a partition of unity there: a gap between their
        // supports takes the far field's light rather than swallowing it.
        far_gathered += ray_weight_;
        continue;
      }
      basis_.evaluate(q, scratch.weights);
      for (const auto& [k, phi] : scratch.weights) {
        if (scratch.near[k])
          near_entries.emplace_back(static_cast<int32_t>(k), phi * ray_weight_);
        else
          far_gathered += phi * ray_weight_;
      }
    }
    return far_gathered;
  }

  // The far entries of receiver j, unscaled, into far_entries; returns the shadow rays traced.
  uint64_t find_far_entries(std::size_t j, const std::vector<uint8_t>& near,
                            std::vector<std::pair<int32_t, double>>& far_entries) const {
    const Site& receiver = sites_[j];
    uint64_t row_rays = 0;
    if (!links_) {
      for (uint32_t k = 0; k < n_; ++k) {
        if (!(effective_area_[k] > 0) || near[k]) continue;
        const double transfer = point_transfer(receiver.position, receiver.normal, sites_[k].position,
                                               sites_[k].normal * effective_area_[k]);
        if (!(transfer > 0)) continue;
        ++row_rays;
        if (sites_see_each_other(scene_, receiver, sites_[k]))
          far_entries.emplace_back(static_cast<int32_t>(k), transfer);
      }
    } else {
      // The links the refinement oracle gave this site as a receiver (their rays were counted there).
      for (std::size_t l = links_->link_start[j]; l < links_->link_start[j + 1]; ++l)
        far_entries.emplace_back(static_cast<int32_t>(links_->links[l].sender), links_->links[l].transfer);
    }
    return row_rays;
  }

  const Scene& scene_;
  const SiteSet& site_set_;
  const std::vector<Site>& sites_;
  const MeshlessBasis& basis_;
  const std::vector<double>& effective_area_;
  const TransferSettings& settings_;
  const HierarchicalLinks* links_;
  std::size_t n_;
  std::vector<uint8_t> object_sides_;
  int strata_;
  double ray_weight_;
  SiteIndex index_;
  double largest_radius_ = 0;
  std::vector<uint32_t> unbounded_;
};

// Every row of S, on this process or across ranks, with its entries counted against the limit.
struct RowBuild {
  RowBuild(const RowGatherer& gatherer, std::size_t n, std::size_t max_entries, ProgressReporter* progress)
      : gatherer(gatherer), n(n), max_entries(max_entries), progress(progress), rows(n), far_scales(n, 0.0) {}

  const RowGatherer& gatherer;
  std::size_t n;
  std::size_t max_entries;
  ProgressReporter* progress;
  std::vector<Row> rows;
  std::vector<double> far_scales;  // per row, 0 where it has no far field
  std::atomic<uint64_t> rays{0};
  std::atomic<std::size_t> kept{0};
  std::atomic<bool> too_many{false};

  void keep(std::size_t entries) {
    if (max_entries > 0 && (kept += entries) > max_entries) too_many = true;
  }

  void compute_here() {
    tbb::parallel_for(std::size_t(0), n, [&](std::size_t j) {
      if (too_many.load(std::memory_order_relaxed)) return;
      rays += gatherer.compute_row(j, rows[j], far_scales);
      keep(rows[j].size());
      if (progress) progress->advance();
    });
  }

  // Across ranks: chunks of receivers handed out dynamically, every rank ends with
  // every row (each rank iterates λ with the whole S), each row exactly as one process has it.
  void compute_across_ranks(Cluster& cluster) {
    const std::size_t chunk = std::clamp<std::size_t>(n / (std::size_t(cluster.size()) * 16), 1, 256);
    const std::size_t tasks = (n + chunk - 1) / chunk;
    std::vector<uint64_t> task_rays(tasks, 0), task_entries(tasks, 0);
    run_task_farm_everywhere(
        cluster, tasks,
        [&](std::size_t task) {
          const std::size_t first = task * chunk, count = std::min(chunk, n - first);
          std::vector<Row> chunk_rows(count);
          std::atomic<uint64_t> chunk_rays{0};
          tbb::parallel_for(std::size_t(0), count, [&](std::size_t k) {
            chunk_rays += gatherer.compute_row(first + k, chunk_rows[k], far_scales);
          });
          std::size_t entries = 0;
          for (const Row& row : chunk_rows) entries += row.size();
          return chunk_bytes(chunk_rays.load(), entries, first, count, chunk_rows.data());
        },
        [&](std::size_t task, std::span<const std::byte> result) {
          const std::size_t first = task * chunk, count = std::min(chunk, n - first);
          ByteReader reader(result);
          task_rays[task] = reader.get<uint64_t>();
          task_entries[task] = reader.get<uint64_t>();
          keep(task_entries[task]);
          const std::vector<double> scales = reader.get_array<double>();
          std::copy(scales.begin(), scales.end(), far_scales.begin() + static_cast<std::ptrdiff_t>(first));
          for (std::size_t k = 0; k < count; ++k) {
            Row row = reader.get_array<Entry>();
            // Past the limit nothing more is kept (the build is refused below): memory stays bounded.
            rows[first + k] = too_many ? Row() : std::move(row);
          }
          if (progress) progress->advance(count);
        },
        [&](std::size_t task) {
          const std::size_t first = task * chunk, count = std::min(chunk, n - first);
          return chunk_bytes(task_rays[task], task_entries[task], first, count, rows.data() + first);
        });
    uint64_t rays_elsewhere = 0;
    for (const uint64_t r : task_rays) rays_elsewhere += r;
    rays = rays_elsewhere;  // every row's rays, wherever it was computed
  }

  // A chunk's rows as bytes: what a rank sends, and what rank 0 rebuilds from `rows` to pass on.
  // The header holds the chunk's entry count as computed: past the limit rank 0 keeps no rows,
  // and every rank must still count them to refuse the matrix alike.
  Bytes chunk_bytes(uint64_t chunk_rays, uint64_t chunk_entries, std::size_t first, std::size_t count,
                    const Row* chunk_rows) const {
    ByteWriter writer;
    writer.put<uint64_t>(chunk_rays);
    writer.put<uint64_t>(chunk_entries);
    writer.put_array(std::vector<double>(far_scales.begin() + static_cast<std::ptrdiff_t>(first),
                                         far_scales.begin() + static_cast<std::ptrdiff_t>(first + count)));
    for (std::size_t k = 0; k < count; ++k) writer.put_array(chunk_rows[k]);
    return writer.take();
  }
};

// Rows straight into the compressed row storage (no triplet list: at 20,000 sites that list
// alone would take gigabytes), each row's memory released as it is copied.
void store_rows(std::vector<Row>& rows, std::size_t columns, TransferMatrix& result) {
  const std::size_t n = rows.size();
  std::size_t total = 0;
  for (const auto& row : rows) total += row.size();
  result.S.resize(static_cast<int32_t>(n), static_cast<int32_t>(columns));
  result.S.reserve(static_cast<Eigen::Index>(total));
  for (std::size_t j = 0; j < n; ++j) {
    result.S.startVec(static_cast<int32_t>(j));
    for (const auto& [k, value] : rows[j]) {
      result.S.insertBack(static_cast<int32_t>(j), k) = value;
      result.cluster_links += static_cast<std::size_t>(k) >= n;
    }
    Row().swap(rows[j]);
  }
  result.S.finalize();
}

// What the hierarchical transport adds to S: the clusters' radiosity from their children's, the
// coarse receivers' links and the tree to push what they gather down to the sites.
void store_hierarchy(const SiteHierarchy& hierarchy, const SenderClusters& clusters,
                     const HierarchicalLinks& links, const std::vector<double>& far_scales, std::size_t n,
                     TransferMatrix& result) {
  const std::size_t columns = hierarchy.node_count();
  // A cluster's radiosity: the area-weighted mean of its children's.
  result.cluster_start.push_back(0);
  for (uint32_t node = static_cast<uint32_t>(n); node < columns; ++node) {
    for (const uint32_t child : hierarchy.children(node))
      if (clusters.area[node] > 0 && clusters.area[child] > 0)
        result.cluster_terms.emplace_back(static_cast<int32_t>(child),
                                          static_cast<float>(clusters.area[child] / clusters.area[node]));
    result.cluster_start.push_back(static_cast<uint32_t>(result.cluster_terms.size()));
  }
  // The coarse receivers' links, unscaled (each site scales what its ancestors bring by its own
  // far-field scale), and the tree to push them down.
  const std::size_t coarse = columns - n;
  result.receiver_links.resize(static_cast<int32_t>(coarse), static_cast<int32_t>(columns));
  result.receiver_links.reserve(static_cast<Eigen::Index>(links.links.size() - links.link_start[n]));
  for (std::size_t c = n; c < columns; ++c) {
    result.receiver_links.startVec(static_cast<int32_t>(c - n));
    for (std::size_t l = links.link_start[c]; l < links.link_start[c + 1]; ++l)
      result.receiver_links.insertBack(static_cast<int32_t>(c - n),
                                       static_cast<int32_t>(links.links[l].sender)) =
          static_cast<float>(links.links[l].transfer);
  }
  result.receiver_links.finalize();
  result.cluster_links += static_cast<std::size_t>(result.receiver_links.nonZeros());
  result.parent.resize(columns);
  for (uint32_t node = 0; node < columns; ++node) result.parent[node] = hierarchy.parent(node);
  result.push_scale = far_scales;
}

}  // namespace

TransferMatrix compute_transfer_matrix(const Scene& scene, const SiteSet& site_set,
                                       const MeshlessBasis& basis, const std::vector<double>& effective_area,
                                       const TransferSettings& settings, Cluster* cluster,
                                       ProgressReporter* progress, const SiteHierarchy* hierarchy) {
  check_transfer_inputs(site_set, effective_area, settings, hierarchy);
  const std::size_t max_entries = settings.max_entries;
  const auto start = std::chrono::steady_clock::now();
  const std::size_t n = site_set.sites.size();
  const std::size_t columns = hierarchy ? hierarchy->node_count() : n;
  const SenderClusters clusters =
      hierarchy ? sender_clusters(*hierarchy, site_set, effective_area, settings.near_field)
                : SenderClusters();
  HierarchicalLinks links;
  if (hierarchy)
    links = refine_links(LinkRefinement{scene, site_set, *hierarchy, clusters, settings, n}, cluster);
  const RowGatherer gatherer(scene, site_set, basis, effective_area, settings, hierarchy ? &links : nullptr);
  RowBuild build(gatherer, n, max_entries, progress);
  if (hierarchy)
    build.keep(links.links.size() - links.link_start[n]);  // the coarse receivers' links are kept too
  if (!cluster || !cluster->distributed())
    build.compute_here();
  else
    build.compute_across_ranks(*cluster);
  if (build.too_many)
    throw std::invalid_argument(
        "transfer matrix: more than " + std::to_string(max_entries) +
        " entries; raise meshless.spacing (fewer sites) (or raise render.memory_limit_mib: 16 "
        "bytes an entry)");
  TransferMatrix result;
  store_rows(build.rows, columns, result);
  if (hierarchy) store_hierarchy(*hierarchy, clusters, links, build.far_scales, n, result);
  result.visibility_rays = build.rays + links.rays;
  result.gather_rays = static_cast<uint64_t>(n) * static_cast<uint64_t>(settings.gather_rays);
  double scale_sum = 0;
  std::size_t scaled_rows = 0;
  for (const double scale : build.far_scales)
    if (scale > 0) scale_sum += scale, ++scaled_rows;
  result.far_field_scale = scaled_rows > 0 ? scale_sum / static_cast<double>(scaled_rows) : 1.0;
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

void TransferMatrix::pushed_values(const std::vector<Color>& senders, std::vector<Color>& pushed) const {
  const auto n = static_cast<std::size_t>(S.rows()), columns = static_cast<std::size_t>(S.cols());
  pushed.assign(columns, Color());
  if (receiver_links.rows() == 0) return;
  tbb::parallel_for(std::size_t(n), columns, [&](std::size_t c) {
    Color gathered;
    for (Eigen::SparseMatrix<float, Eigen::RowMajor, int32_t>::InnerIterator entry(
             receiver_links, static_cast<int32_t>(c - n));
         entry; ++entry)
      gathered += senders[static_cast<std::size_t>(entry.col())] * static_cast<double>(entry.value());
    pushed[c] = gathered;
  });
  // Parents before children (a parent's index is larger): each node adds what its ancestors gathered.
  for (std::size_t c = columns; c-- > n;)
    if (parent[c] != UINT32_MAX) pushed[c] += pushed[parent[c]];
  for (std::size_t j = 0; j < n; ++j)
    pushed[j] = parent[j] == UINT32_MAX ? Color() : pushed[parent[j]] * push_scale[j];
}

TransferSolution solve_transfer(const TransferMatrix& transfer, const std::vector<Color>& albedo,
                                const std::vector<Color>& eta, double tolerance, std::size_t max_iterations,
                                ProgressReporter* progress, const TransferIterationCallback& on_iteration) {
  const auto n = static_cast<std::size_t>(transfer.S.rows());
  if (albedo.size() != n || eta.size() != n)
    throw std::invalid_argument("meshless solve: " + std::to_string(n) + " sites, " +
                                std::to_string(albedo.size()) + " albedos, " + std::to_string(eta.size()) +
                                " direct terms");
  TransferSolution solution;
  solution.lambda = eta;
  double largest_eta = 0;
  for (const Color& e : eta)
    largest_eta = std::max({largest_eta, std::fabs(e.r), std::fabs(e.g), std::fabs(e.b)});
  std::vector<Color> next(n), senders, pushed;
  const bool clustered = static_cast<std::size_t>(transfer.S.cols()) != n;
  for (std::size_t iteration = 0; iteration < max_iterations; ++iteration) {
    // Hierarchical transport: the clusters' radiosity from λ first.
    if (clustered) transfer.sender_values(solution.lambda, senders);
    const std::vector<Color>& sender = clustered ? senders : solution.lambda;
    // The coarse receivers' links, each node's gathered light plus its ancestors' (pushed down).
    if (clustered) transfer.pushed_values(sender, pushed);
    // λ' = η + Q S λ, each row by one thread.
    tbb::parallel_for(std::size_t(0), n, [&](std::size_t j) {
      Color gathered = clustered ? pushed[j] : Color();
      for (Eigen::SparseMatrix<float, Eigen::RowMajor, int32_t>::InnerIterator entry(transfer.S,
                                                                                     static_cast<int32_t>(j));
           entry; ++entry)
        gathered += sender[static_cast<std::size_t>(entry.col())] * static_cast<double>(entry.value());
      next[j] = eta[j] + albedo[j] * gathered;
    });
    double change = 0, largest = 0;
    for (std::size_t j = 0; j < n; ++j)
      for (int c = 0; c < 3; ++c) {
        change = std::max(change, std::fabs(next[j][c] - solution.lambda[j][c]));
        largest = std::max(largest, std::fabs(next[j][c]));
      }
    solution.lambda.swap(next);
    solution.iterations = iteration + 1;
    solution.final_change = largest > 0 ? change / largest : 0;
    if (on_iteration) on_iteration(solution.iterations, solution.lambda);
    if (progress) {
      const auto done = static_cast<uint64_t>(1000 * convergence_progress(solution.final_change, tolerance));
      progress->set_detail(
          fmt::format("change {:.3g} after {} iterations", solution.final_change, solution.iterations));
      progress->advance_to(done);
    }
    // Diverging (a row of R summing past 1) or overflowed: stop and say so.
    if (!std::isfinite(largest) || !std::isfinite(change) || largest > 1e12 * std::max(largest_eta, 1e-300)) {
      solution.diverged = true;
      break;
    }
    if (solution.final_change <= tolerance) {
      solution.converged = true;
      break;
    }
  }
  return solution;
}

}  // namespace candela
