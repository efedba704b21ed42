#include "radiosity/hierarchical_radiosity.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <span>
#include <vector>

#include "distributed/cluster.h"
#include "math/constants.h"
#include "math/pcg32.h"
#include "math/spherical_harmonics.h"
#include "radiosity/diagnostics.h"
#include "radiosity/first_shot.h"
#include "radiosity/form_factor_memory.h"
#include "radiosity/radiosity_hierarchy.h"
#include "radiosity/ray_cast_form_factors.h"
#include "radiosity/solve.h"
#include "radiosity/triangle_occluders.h"
#include "sampling/warps.h"
#include "scene/scene.h"
#include "util/cancellation.h"
#include "util/progress.h"
#include "util/statistics.h"

namespace candela {
namespace {

struct Link {
  uint32_t receiver = 0, source = 0;
  float factor = 0;       // K: irradiance at the receiver per unit radiosity (or intensity) of the source
  float uncertainty = 0;  // ΔK, what the oracle weighs
  // A link with a cluster: the unit direction from the receiver toward the source. Surface to
  // surface: the factor at the receiver's three corners, of the linear function through its values
  // at the centroids of the three corner children (factor is their mean), which the irradiance is
  // pushed down by.
  std::array<float, 3> values{};
  uint8_t flags = 0;
};
// kPending: a link with a cluster whose factor is the unoccluded point kernel, its visibility and
// correction not yet applied (HierarchicalSolver::transport).
constexpr uint8_t kPartialVisibility = 1, kUnseparated = 2, kDead = 4, kPending = 8;

enum class Split : uint8_t { none, receiver, source, both };

constexpr int kVisibilityRays = 4;
// Input triangles of curved shapes: chords within this fraction of the scene size of the surface,
// with at most this many times radiosity.segments per turn.
constexpr double kChordFraction = 1e-3;
constexpr int kChordSegmentsPerSegment = 4;
// A surface-to-surface link is also split while its factor is uncertain by more than this many
// times refinement_tolerance of itself (5e-5: 2 %) — unless the power it may be wrong by is below
// kRelativeGate ε, too little to matter (the furnace within 0.4 % at the defaults).
constexpr double kRelativeTolerancePerPowerTolerance = 400;
constexpr double kRelativeGate = 0.01;
// The same for a link with a cluster: the irradiance it may be wrong by against the radiosity the
// receiver shows, above ε/10 of power (the dragon within 1 % of the path tracer; at ε/100 the
// 10,584 spheres took 163 s instead of 47).
constexpr double kClusterGate = 0.1;
constexpr int kMaxRefinementRounds = 3;
// The surfaces that stand for a cluster in a link's correction and visibility
// (HierarchicalSolver::transport): this many input triangles at the source end and this many at
// the receiving end (the source's harmonics vary more across it than a receiver's cosines), drawn
// in proportion to their area (or all of them, in a cluster of fewer).
constexpr uint32_t kCorrectionSources = 16, kCorrectionReceivers = 8;
// The correction is at most this (a link's kernel near zero where its surfaces do exchange light:
// the harmonics' lobe beside its peak); it is 0 where no pair of them faces the other.
constexpr double kMostCorrection = 4;
// A source surface whose longest edge is above this fraction of its distance to a receiving one
// is integrated in closed form in the correction, not taken as a point.
constexpr double kPointMemberEdge = 0.25;
// Nodes whose radii add up to less than this fraction of their distance are corrected as far apart
// (direction by direction, not pair by pair).
constexpr double kFarField = 0.15;

// Surfaces standing for (part of) a node in the point kernel's correction, each with the share of
// the node's area it stands for and (sources) the radiosity it sends with.
struct KernelMember {
  const RadiositySurface* surface = nullptr;
  double share = 0;   // of the node's (reflecting) area it stands for
  double weight = 0;  // the radiosity it sends with (sources)
};
struct KernelMembers {
  std::array<KernelMember, kCorrectionSources> member;
  uint32_t count = 0;
};

class HierarchicalSolver {
 public:
  HierarchicalSolver(const Scene& scene, const RadiositySettings& settings,
                     const RadiositySolveOptions& options, RadiosityHierarchy& hierarchy,
                     std::unique_ptr<TriangleOccluders> occluders)
      : scene_(scene),
        settings_(settings),
        options_(options),
        tree_(hierarchy),
        occluders_(std::move(occluders)) {
    const double element_size = settings.element_size > 0 ? settings.element_size
                                : settings.patch_size > 0 ? settings.patch_size / 2
                                                          : hierarchy.scene_size / 16;
    min_edge_ = settings.min_element_size > 0 ? settings.min_element_size : element_size / 8;
    offset_ = 1e-9 * hierarchy.scene_size;
    double area = 0, reflecting = 0;
    cumulative_area_.reserve(hierarchy.input_order.size());
    cumulative_reflecting_.reserve(hierarchy.input_order.size());
    for (const uint32_t input : hierarchy.input_order) {
      const HierarchyNode& root = hierarchy.nodes[hierarchy.root_of_input[input]];
      cumulative_area_.push_back(area += root.area);
      cumulative_reflecting_.push_back(reflecting += root.area * root.reflectance_max);
    }
  }

  RadiositySolveResult solve();

 private:
  bool stopped() const { return cancelled_anywhere(options_.cluster); }
  bool can_split(uint32_t node) const { return tree_.nodes[node].is_cluster || tree_.edge(node) > min_edge_; }
  uint32_t children_of(uint32_t node) {  // splits a surface leaf when it has to
    if (tree_.nodes[node].child_count > 0) return tree_.nodes[node].first_child;
    return tree_.split(scene_, node);
  }

  void compute_direct(std::span<const uint32_t> nodes);
  void grow_state();
  void split_for_direct_light();
  bool evaluate(Link& link) const;
  // The link's own random stream (its rays' jitter), whatever the thread or the order of links.
  Pcg32 link_stream(const Link& link) const {
    return Pcg32(options_.seed ^ 0x6a09e667f3bcc909ULL,
                 (static_cast<uint64_t>(link.receiver) << 32) | link.source);
  }
  void transport(Link& link) const;
  KernelMembers kernel_members(uint32_t node, uint32_t count, bool receiving) const;
  bool evaluate_surfaces(Link& link, Pcg32& random) const;
  Split decide(const Link& link) const;
  double power_error(const Link& link) const;
  double source_magnitude(const Link& link) const;
  double relative_error(const Link& link) const;
  std::size_t refine(std::vector<uint32_t> candidates);
  bool within_memory() const;
  void sort_links();
  void gather();
  void push();
  double update_leaves(double& largest);
  void pull();
  // A surface's irradiance: the mean of its corners' (the linear function's mean), at least 0.
  Color leaf_irradiance(uint32_t node) const {
    return max((down_[node][0] + down_[node][1] + down_[node][2]) * (1.0 / 3), Color());
  }
  std::vector<double> row_sums();
  bool visible(const Vec3& from, const Vec3& to) const;
  uint32_t input_at(const HierarchyCluster& cluster, double fraction, bool reflecting) const;
  RadiositySolveResult result(const std::vector<double>& sums) const;

  const Scene& scene_;
  const RadiositySettings& settings_;
  const RadiositySolveOptions& options_;
  RadiosityHierarchy& tree_;
  std::unique_ptr<TriangleOccluders> occluders_;  // released before the result is assembled
  double min_edge_ = 0, offset_ = 0, epsilon_ = 0;
  double relative_tolerance_ = 0;
  bool first_round_ = true;
  bool memory_stopped_ = false;

  std::vector<Link> links_;
  std::vector<uint32_t> link_start_;  // links_ sorted by receiver: the receivers' ranges
  std::vector<uint32_t> receivers_;
  // Irradiance at a surface's three corners, linear across it (the links' own and, down_, with its
  // ancestors'): what a leaf takes at its centroid.
  using CornerIrradiance = std::array<Color, 3>;
  std::vector<Color> radiosity_;
  std::vector<CornerIrradiance> gathered_, down_;
  std::vector<ShColor> cluster_out_, cluster_in_, cluster_down_;
  // The input triangles' areas, and their reflecting areas A × the largest channel of ρ, summed in
  // input_order: where a cluster's members are drawn in proportion to either.
  std::vector<double> cumulative_area_, cumulative_reflecting_;
  std::vector<Color> cluster_power_;
  std::size_t links_made_ = 0, surface_links_made_ = 0, transported_ = 0;
  double refine_seconds_ = 0, direct_seconds_ = 0, gather_seconds_ = 0;
  std::size_t rounds_ = 0;
};

void HierarchicalSolver::grow_state() {
  const std::size_t old = radiosity_.size();
  radiosity_.resize(tree_.nodes.size());
  gathered_.resize(tree_.nodes.size());
  down_.resize(tree_.nodes.size());
  // A new node starts from its parent's radiosity (its own emission and first shot before any
  // solve), what the oracle weighs until the next solve.
  for (std::size_t i = old; i < tree_.nodes.size(); ++i) {
    const HierarchyNode& node = tree_.nodes[i];
    if (node.is_cluster) continue;
    const RadiositySurface& s = tree_.surface(static_cast<uint32_t>(i));
    radiosity_[i] = first_round_ || node.parent == kNoNode || tree_.nodes[node.parent].is_cluster
                        ? s.emission + s.first_shot
                        : radiosity_[node.parent];
  }
  cluster_out_.resize(tree_.clusters.size());
  cluster_in_.resize(tree_.clusters.size());
  cluster_down_.resize(tree_.clusters.size());
  cluster_power_.resize(tree_.clusters.size());
}

void HierarchicalSolver::compute_direct(std::span<const uint32_t> nodes) {
  Stopwatch time;
  const StratumJitter jitter{true, options_.seed};
  tbb::parallel_for(std::size_t(0), nodes.size(), [&](std::size_t k) {
    HierarchySurface& made = tree_.surfaces[tree_.nodes[nodes[k]].payload];
    if (made.direct_done) return;
    std::array<Color, 4> direct{};
    if (!scene_.lights.empty() || scene_.environment_light)
      direct = direct_irradiance_samples(scene_, made.surface, jitter);
    Color sum, low = direct[0], high = direct[0];
    for (const Color& sample : direct) {
      sum += sample;
      low = min(low, sample);
      high = max(high, sample);
    }
    made.surface.first_shot = made.surface.reflectance * sum * 0.25;
    made.direct_error = made.surface.area * (made.surface.reflectance * (high - low)).max_component();
    made.direct_done = true;
  });
  direct_seconds_ += time.seconds();
}

void HierarchicalSolver::split_for_direct_light() {
  std::vector<uint32_t> check;
  for (uint32_t i = 0; i < tree_.nodes.size(); ++i)
    if (!tree_.nodes[i].is_cluster && tree_.is_leaf(i)) check.push_back(i);
  compute_direct(check);
  while (!check.empty() && !stopped()) {
    std::vector<uint32_t> next;
    for (const uint32_t node : check) {
      if (!tree_.is_leaf(node) || !can_split(node) ||
          !(tree_.surfaces[tree_.nodes[node].payload].direct_error > epsilon_))
        continue;
      const uint32_t first = children_of(node);
      for (uint32_t c = first; c < first + 4; ++c) next.push_back(c);
    }
    compute_direct(next);
    grow_state();
    check = std::move(next);
  }
}

bool HierarchicalSolver::visible(const Vec3& from, const Vec3& to) const {
  const Vec3 between = to - from;
  const double distance = length(between);
  if (!(distance > 4 * offset_)) return true;
  const Ray ray{from, between / distance, 1e-5 * distance + offset_, distance * (1 - 1e-5) - offset_};
  return !occluders_->accelerator().occluded(ray);
}

// The root of the input triangle at `fraction` (0 … 1) of a cluster's cumulative area, or of its
// reflecting area (by area where nothing inside reflects).
uint32_t HierarchicalSolver::input_at(const HierarchyCluster& cluster, double fraction,
                                      bool reflecting) const {
  const std::size_t first = cluster.first_input, last = first + cluster.input_count - 1;
  const std::vector<double>& cumulative =
      reflecting && cumulative_reflecting_[last] > (first > 0 ? cumulative_reflecting_[first - 1] : 0)
          ? cumulative_reflecting_
          : cumulative_area_;
  const double before = first > 0 ? cumulative[first - 1] : 0;
  const auto begin = cumulative.begin() + static_cast<std::ptrdiff_t>(first);
  const auto end = cumulative.begin() + static_cast<std::ptrdiff_t>(last);
  const auto found = std::upper_bound(begin, end, before + fraction * (cumulative[last] - before));
  return tree_.root_of_input[tree_.input_order[static_cast<std::size_t>(found - cumulative.begin())]];
}

// A point drawn uniformly on a surface (a visibility ray's end).
Vec3 random_point(const RadiositySurface& s, Pcg32& random) {
  const Vec2 b = square_to_uniform_triangle({random.next_double(), random.next_double()});
  return s.corners[0] * b.x + s.corners[1] * b.y + s.corners[2] * (1 - b.x - b.y);
}

bool HierarchicalSolver::evaluate_surfaces(Link& link, Pcg32& random) const {
  const RadiositySurface& receiver = tree_.surface(link.receiver);
  const RadiositySurface& source = tree_.surface(link.source);
  // Nothing passes when the source lies wholly on or behind the receiver's plane, or the receiver
  // on or behind the source's (surfaces are one-sided, 000 §6).
  const double tolerance = offset_;
  const auto in_front = [&](const RadiositySurface& of, const RadiositySurface& plane) {
    return std::any_of(of.corners.begin(), of.corners.end(),
                       [&](const Vec3& c) { return dot(c - plane.centroid, plane.normal) > tolerance; });
  };
  if (!in_front(source, receiver) || !in_front(receiver, source)) return false;
  const std::array<Vec3, 4> points = tree_.child_centroids(link.receiver);
  std::array<double, 4> factor{};
  for (std::size_t k = 0; k < 4; ++k)
    factor[k] = point_to_polygon_form_factor(points[k], receiver.normal, source.corners);
  // The linear function through the corner children's centroids (barycentric (2/3, 1/6, 1/6) and
  // its turns) has the corner values 2 f_k − mean; its mean over the triangle is the mean of f_0..2.
  const double mean = (factor[0] + factor[1] + factor[2]) / 3;
  if (!(mean > 0) && !(factor[3] > 0)) return false;
  std::array<double, 3> at_corner{};
  // How far the factor is from linear: at the middle child's centroid, and at the corners (where
  // it climbs toward an edge shared with the source's wall: a furnace's edges were ±15 % off).
  double nonlinearity = std::fabs(factor[3] - mean);
  for (std::size_t k = 0; k < 3; ++k) {
    at_corner[k] = 2 * factor[k] - mean;
    const double exact = point_to_polygon_form_factor(receiver.corners[k], receiver.normal, source.corners);
    nonlinearity = std::max(nonlinearity, std::isfinite(exact) ? std::fabs(exact - at_corner[k]) : mean);
  }
  double seen = 0, weight = 0;
  int visible_rays = 0;
  for (std::size_t k = 0; k < 4; ++k) {
    const bool v = visible(points[k], random_point(source, random));
    visible_rays += v ? 1 : 0;
    weight += factor[k];
    if (v) seen += factor[k];
  }
  const double visibility = weight > 0 ? seen / weight : 0;
  const bool partial = visible_rays < kVisibilityRays;
  link.factor = 0;
  link.uncertainty = static_cast<float>(std::max(mean, nonlinearity));
  link.flags = kPartialVisibility;
  // Hidden from all four rays: nothing passes, unless the power it could carry makes four rays too
  // few to say (then it is split like a partly visible link).
  if (visible_rays == 0) return power_error(link) > epsilon_;
  link.factor = static_cast<float>(mean * visibility);
  for (std::size_t k = 0; k < 3; ++k) link.values[k] = static_cast<float>(at_corner[k] * visibility);
  link.uncertainty = static_cast<float>(partial ? std::max(nonlinearity, mean) : nonlinearity);
  link.flags = partial ? kPartialVisibility : 0;
  return true;
}

KernelMembers HierarchicalSolver::kernel_members(uint32_t node, uint32_t count, bool receiving) const {
  KernelMembers out;
  const auto add = [&](uint32_t surface_node, double share) {
    out.member[out.count++] = {&tree_.surface(surface_node), share, radiosity_[surface_node].max_component()};
  };
  const HierarchyNode& n = tree_.nodes[node];
  if (!n.is_cluster) {
    add(node, 1);
    return out;
  }
  const HierarchyCluster& cluster = tree_.clusters[n.payload];
  if (cluster.input_count <= count) {  // every input triangle, for its own (reflecting) area
    for (uint32_t k = 0; k < cluster.input_count; ++k) {
      const uint32_t root = tree_.root_of_input[tree_.input_order[cluster.first_input + k]];
      add(root, tree_.nodes[root].area * (receiving ? tree_.nodes[root].reflectance_max : 1));
    }
  } else {
    // Stratified along the cluster's input triangles in proportion to their area (sources) or
    // their reflecting area (receivers: only the light a surface reflects matters), each standing
    // for an equal share: a wall's large triangle beside a mesh's many small ones is drawn as often
    // as its area says, and a small white card beside a black sphere is drawn every time.
    for (uint32_t k = 0; k < count; ++k) add(input_at(cluster, (k + 0.5) / count, receiving), 1);
  }
  // A source that sends nothing yet (before the first solve) is weighed by area alone.
  double sent = 0;
  for (uint32_t k = 0; k < out.count; ++k) sent += out.member[k].weight;
  if (!(sent > 0))
    for (uint32_t k = 0; k < out.count; ++k) out.member[k].weight = 1;
  return out;
}

bool HierarchicalSolver::evaluate(Link& link) const {
  const HierarchyNode& receiver = tree_.nodes[link.receiver];
  const HierarchyNode& source = tree_.nodes[link.source];
  Pcg32 random = link_stream(link);
  link.flags = 0;
  link.factor = link.uncertainty = 0;
  if (!receiver.is_cluster && !source.is_cluster) return evaluate_surfaces(link, random);
  const Vec3 between = source.centre - receiver.centre;
  const double distance = length(between);
  // The point-to-point kernel holds for nodes apart: closer ones are split before any transport.
  if (!(distance > receiver.radius + source.radius)) {
    link.flags = kUnseparated;
    return true;
  }
  const Vec3 w = between / distance;
  link.values = {static_cast<float>(w.x), static_cast<float>(w.y), static_cast<float>(w.z)};
  const double inverse_square = 1 / (distance * distance);
  double factor = 0, bound = 0;
  if (!receiver.is_cluster) {
    const Vec3& n = tree_.surface(link.receiver).normal;
    if (dot(between, n) < -source.radius) return false;  // the cluster wholly behind the receiver
    factor = std::max(0.0, dot(n, w)) * inverse_square;
    bound = inverse_square;
  } else if (!source.is_cluster) {
    const Vec3& n = tree_.surface(link.source).normal;
    if (dot(-between, n) < -receiver.radius) return false;  // the cluster wholly behind the source
    factor = source.area * std::max(0.0, -dot(n, w)) * inverse_square / kPi;
    bound = source.area * inverse_square / kPi;
  } else {
    factor = bound = inverse_square;
  }
  link.factor = static_cast<float>(factor);
  link.uncertainty = static_cast<float>(bound);
  link.flags = kPending;
  return true;
}

// A link with a cluster that refinement kept: its factor corrected and times its visibility (the
// oracle weighs a cluster link by its bound alone, so this waits until the link is known to stay,
// a third of those evaluated).
//
// The correction. A link with a cluster moves light by a point kernel — the source's intensity
// toward the receiver's centre over d², the receiver's cosine (a surface's, or the band-2
// harmonics' of its surfaces) — which is off by about (r/d)² (a sphere's cap at d = 2.7 r was 12 %
// bright: the perspective shows less of it than the parallel projection the intensity is) and by
// the harmonics' truncation (6 % at a lobe's peak), the same sign for every link toward a small
// receiver (a 0.2 receiver before a sphere was 8 % bright at h = 5). The factor is scaled by the
// ratio of the power that surfaces standing for both ends exchange pair by pair (each pair's own
// point kernel, or Lambert's closed form over a source surface large for its distance, weighed by
// the source's radiosity at the link's making) to what the link's kernel gives the same surfaces.
//
// The visibility. Its rays join pairs of those surfaces drawn in proportion to what each pair
// exchanges, so that it is the kernel-weighted visible fraction, as a surface link's is, and no ray
// goes to a surface that cannot see the other end (a sphere's far side is hidden by its near one,
// while the kernel counts only the pairs that face).
void HierarchicalSolver::transport(Link& link) const {
  const HierarchyNode& receiver = tree_.nodes[link.receiver];
  const HierarchyNode& source = tree_.nodes[link.source];
  Pcg32 random = link_stream(link);
  const Vec3 w(link.values[0], link.values[1], link.values[2]);
  const double distance = length(source.centre - receiver.centre);
  const KernelMembers receivers = kernel_members(link.receiver, kCorrectionReceivers, true),
                      sources = kernel_members(link.source, kCorrectionSources, false);
  // What the link gives the members: the intensity of the source's harmonics (a surface's own
  // cosine) toward −w, and the receiving cosines (push's band-2 irradiance of a delta, in a
  // cluster), over d².
  double intensity = 0;
  if (source.is_cluster) {
    ShBasis coefficients{};
    for (uint32_t t = 0; t < sources.count; ++t) {
      const KernelMember& from = sources.member[t];
      const ShBasis n = sh_basis(from.surface->normal);
      for (std::size_t k = 0; k < 9; ++k)
        coefficients[k] += from.share * from.weight * kClampedCosineBands[k] * n[k];
    }
    const ShBasis away = sh_basis(-w);
    for (std::size_t k = 0; k < 9; ++k) intensity += coefficients[k] * away[k];
    intensity = std::max(0.0, intensity);
  } else {
    intensity = sources.member[0].weight * std::max(0.0, -dot(sources.member[0].surface->normal, w));
  }
  const ShBasis toward_source = sh_basis(w);
  double receiving = 0;
  for (uint32_t r = 0; r < receivers.count; ++r) {
    const KernelMember& at = receivers.member[r];
    double cosine = std::max(0.0, dot(at.surface->normal, w));
    if (receiver.is_cluster) {
      const ShBasis n = sh_basis(at.surface->normal);
      cosine = 0;
      for (std::size_t k = 0; k < 9; ++k) cosine += kClampedCosineBands[k] * toward_source[k] * n[k];
      cosine = std::max(0.0, cosine);
    }
    receiving += at.share * cosine;
  }
  const double kernel = intensity * receiving / (distance * distance);
  // What the members exchange, pair by pair: near ends pair by pair; far ones (the distance and
  // the direction hardly change across either) as the exact intensity toward −w times the exact
  // receiving cosines, over d².
  std::array<double, kCorrectionReceivers * kCorrectionSources> pair{};
  std::array<double, kCorrectionReceivers> receiving_weight{};
  std::array<double, kCorrectionSources> sending_weight{};
  const bool far = receiver.radius + source.radius < kFarField * distance;
  double exact = 0, sent = 0, received = 0;  // sent, received: the far ends' weights summed
  if (far) {
    for (uint32_t t = 0; t < sources.count; ++t) {
      const KernelMember& from = sources.member[t];
      sent += sending_weight[t] = from.share * from.weight * std::max(0.0, -dot(from.surface->normal, w));
    }
    for (uint32_t r = 0; r < receivers.count; ++r)
      received += receiving_weight[r] =
          receivers.member[r].share * std::max(0.0, dot(receivers.member[r].surface->normal, w));
    exact = sent * received / (distance * distance);
  } else {
    std::array<double, kCorrectionSources> closed_form_within{};  // squared distances
    for (uint32_t t = 0; t < sources.count; ++t) {
      const double edge = longest_edge(*sources.member[t].surface) / kPointMemberEdge;
      closed_form_within[t] = edge * edge;
    }
    for (uint32_t r = 0; r < receivers.count; ++r) {
      const KernelMember& at = receivers.member[r];
      const RadiositySurface& a = *at.surface;
      for (uint32_t t = 0; t < sources.count; ++t) {
        const KernelMember& from = sources.member[t];
        const RadiositySurface& f = *from.surface;
        const Vec3 between = a.centroid - f.centroid;
        const double squared = dot(between, between);
        if (!(squared > 0)) continue;
        const double weight = at.share * from.share * from.weight;
        double value = 0;
        if (closed_form_within[t] > squared) {
          if (dot(f.normal, between) > 0)  // per unit of the source's area
            value = weight * kPi * point_to_polygon_form_factor(a.centroid, a.normal, f.corners) / f.area;
        } else {
          const Vec3 u = between / std::sqrt(squared);
          value = weight * std::max(0.0, dot(f.normal, u)) * std::max(0.0, -dot(a.normal, u)) / squared;
        }
        exact += pair[r * kCorrectionSources + t] = value;
      }
    }
  }
  if (!(exact > 0)) {  // no pair of the members faces the other: nothing passes
    link.factor = 0;
    link.flags = 0;
    return;
  }
  const double correction = kernel > 0 ? std::min(exact / kernel, kMostCorrection) : 1.0;
  // Stratified draws of the pairs in proportion to what they exchange.
  const auto draw = [&](const double* weights, uint32_t count, double total, double u) {
    double sum = 0;
    for (uint32_t k = 0; k + 1 < count; ++k)
      if ((sum += weights[k]) > u * total) return k;
    return count - 1;
  };
  int visible_rays = 0;
  for (int k = 0; k < kVisibilityRays; ++k) {
    const double u = (k + random.next_double()) / kVisibilityRays;
    uint32_t r = 0, t = 0;
    if (far) {
      r = draw(receiving_weight.data(), receivers.count, received, u);
      t = draw(sending_weight.data(), sources.count, sent, random.next_double());
    } else {
      const uint32_t chosen = draw(pair.data(), receivers.count * kCorrectionSources, exact, u);
      r = chosen / kCorrectionSources;
      t = chosen % kCorrectionSources;
    }
    // A surface receiver's rays start at its four children's centroids, as a surface link's do.
    const Vec3 at = receiver.is_cluster ? random_point(*receivers.member[r].surface, random)
                                        : tree_.child_centroids(link.receiver)[static_cast<std::size_t>(k)];
    visible_rays += visible(at, random_point(*sources.member[t].surface, random)) ? 1 : 0;
  }
  const double visibility = static_cast<double>(visible_rays) / kVisibilityRays;
  const bool partial = visible_rays > 0 && visible_rays < kVisibilityRays;
  link.factor = static_cast<float>(link.factor * correction * visibility);
  // The uncertainty stays the bound whatever the rays said: one visibility for every surface
  // inside a cluster is uncertain (a cluster may hold a lit box top and the floor hidden under it).
  link.flags = partial ? kPartialVisibility : 0;
}

// The power by which the link's transport is uncertain: ρ_i A_i × the source's radiosity (or
// intensity bound Σ B A / π) × ΔK.
double HierarchicalSolver::power_error(const Link& link) const {
  const HierarchyNode& receiver = tree_.nodes[link.receiver];
  return receiver.reflectance_max * receiver.area * source_magnitude(link) * link.uncertainty;
}

// What a link's factor multiplies at its source: a surface's radiosity, or the bound Σ B A / π of a
// cluster's intensity (the largest channel).
double HierarchicalSolver::source_magnitude(const Link& link) const {
  const HierarchyNode& source = tree_.nodes[link.source];
  return source.is_cluster ? cluster_power_[source.payload].max_component() / kPi
                           : radiosity_[link.source].max_component();
}

// How uncertain a surface-to-surface link's factor is relative to itself. The power oracle alone
// leaves small receivers as wrong as their small share allows, and the errors of the many links
// a receiver keeps at one level add up where they lean alike (toward an edge every far wall's factor
// falls as the near wall's climbs: a furnace's edges were 5 % bright): each link is held to its
// own share.
double HierarchicalSolver::relative_error(const Link& link) const {
  const HierarchyNode& receiver = tree_.nodes[link.receiver];
  const HierarchyNode& source = tree_.nodes[link.source];
  if (!receiver.is_cluster && !source.is_cluster)
    return link.factor > 0 ? link.uncertainty / link.factor : (link.uncertainty > 0 ? kInfinity : 0);
  // A link with a cluster: the irradiance it may be wrong by, reflected, over the radiosity the
  // receiver shows (a small receiver before a large source would otherwise take all its light
  // through clusters, the power oracle finding its share too small to matter).
  const double own = receiver.is_cluster ? cluster_power_[receiver.payload].max_component() / receiver.area
                                         : radiosity_[link.receiver].max_component();
  const double error = receiver.reflectance_max * source_magnitude(link) * link.uncertainty;
  return own > 0 ? error / own : (error > 0 ? kInfinity : 0);
}

Split HierarchicalSolver::decide(const Link& link) const {
  const HierarchyNode& receiver = tree_.nodes[link.receiver];
  const HierarchyNode& source = tree_.nodes[link.source];
  if (link.receiver == link.source) return receiver.is_cluster ? Split::both : Split::none;
  const bool receiver_can = can_split(link.receiver), source_can = can_split(link.source);
  const auto larger = [&] {
    if (receiver_can && (!source_can || receiver.radius >= source.radius)) return Split::receiver;
    return source_can ? Split::source : Split::none;
  };
  if (link.flags & kUnseparated) return larger();
  if (!receiver.is_cluster && !source.is_cluster && source.child_count > 0 && source_can) {
    // The link moves the source's mean radiosity, which is wrong for a receiver that sees one part
    // of the source more than the rest where the radiosity varies across it: the floor beside a
    // wall lit from an opening above sees most of the wall's dark foot (the open room under a sky
    // came out 4 % bright, its floor's reflected light 10 % too much from each wall). Split the
    // source while the power that may be wrong by is above the tolerance.
    Color low = radiosity_[source.first_child], high = low;
    for (uint32_t c = source.first_child + 1; c < source.first_child + source.child_count; ++c) {
      low = min(low, radiosity_[c]);
      high = max(high, radiosity_[c]);
    }
    if (receiver.reflectance_max * receiver.area * link.factor * (high - low).max_component() > epsilon_)
      return Split::source;
  }
  const double power = power_error(link);
  const double gate = (receiver.is_cluster || source.is_cluster) ? kClusterGate : kRelativeGate;
  if (!(power > epsilon_) && !(power > gate * epsilon_ && relative_error(link) > relative_tolerance_))
    return Split::none;
  if (!receiver.is_cluster && !source.is_cluster) {
    // The closed form is exact over the source: splitting it helps only a partial visibility.
    const bool partial = link.flags & kPartialVisibility;
    if (partial && source_can && source.area > receiver.area) return Split::source;
    if (receiver_can) return Split::receiver;
    return partial && source_can ? Split::source : Split::none;
  }
  return larger();
}

bool HierarchicalSolver::within_memory() const {
  const double bytes =
      static_cast<double>(tree_.memory_bytes() + links_.capacity() * sizeof(Link)) +
      static_cast<double>(radiosity_.capacity()) * (sizeof(Color) + 2 * sizeof(CornerIrradiance)) +
      static_cast<double>(cluster_out_.capacity()) * (3 * sizeof(ShColor) + sizeof(Color));
  return bytes < 0.9 * static_cast<double>(form_factor_memory_limit(settings_));
}

// Refines the candidate links, wave by wave: decisions in parallel, splits in link order, the new
// links' factors in parallel (each from its own random stream). Returns the links split.
std::size_t HierarchicalSolver::refine(std::vector<uint32_t> candidates) {
  Stopwatch time;
  std::size_t split_count = 0;
  while (!candidates.empty() && !stopped()) {
    if (!within_memory()) {
      memory_stopped_ = true;
      break;
    }
    std::vector<Split> decision(candidates.size());
    tbb::parallel_for(std::size_t(0), candidates.size(),
                      [&](std::size_t k) { decision[k] = decide(links_[candidates[k]]); });
    std::vector<Link> fresh;
    const std::size_t nodes_before = tree_.nodes.size();
    for (std::size_t k = 0; k < candidates.size(); ++k) {
      if (decision[k] == Split::none) continue;
      ++split_count;
      Link& old = links_[candidates[k]];
      old.flags |= kDead;
      const uint32_t receiver = old.receiver, source = old.source;
      const auto each_child = [&](uint32_t node, auto&& make) {
        const uint32_t first = children_of(node);
        for (uint32_t c = first; c < first + tree_.nodes[node].child_count; ++c) make(c);
      };
      switch (decision[k]) {
        case Split::receiver:
          each_child(receiver, [&](uint32_t c) { fresh.push_back({c, source}); });
          break;
        case Split::source:
          each_child(source, [&](uint32_t c) { fresh.push_back({receiver, c}); });
          break;
        case Split::both:
          each_child(receiver, [&](uint32_t a) {
            each_child(source, [&](uint32_t b) { fresh.push_back({a, b}); });
          });
          break;
        case Split::none:
          break;
      }
    }
    std::vector<uint32_t> made;
    for (auto i = static_cast<uint32_t>(nodes_before); i < tree_.nodes.size(); ++i) made.push_back(i);
    compute_direct(made);
    grow_state();
    std::vector<uint8_t> keep(fresh.size());
    tbb::parallel_for(std::size_t(0), fresh.size(),
                      [&](std::size_t k) { keep[k] = evaluate(fresh[k]) ? 1 : 0; });
    links_made_ += fresh.size();
    for (const Link& link : fresh)
      if (!tree_.nodes[link.receiver].is_cluster && !tree_.nodes[link.source].is_cluster)
        ++surface_links_made_;
    // The split links go now (a round makes several times the links it keeps); the new ones are
    // the next wave's candidates, at the end.
    std::erase_if(links_, [](const Link& link) { return (link.flags & kDead) != 0; });
    const std::size_t kept_before = links_.size();
    for (std::size_t k = 0; k < fresh.size(); ++k)
      if (keep[k]) links_.push_back(fresh[k]);
    candidates.resize(links_.size() - kept_before);
    for (std::size_t k = 0; k < candidates.size(); ++k)
      candidates[k] = static_cast<uint32_t>(kept_before + k);
  }
  std::erase_if(links_, [](const Link& link) { return (link.flags & kDead) != 0; });
  links_.shrink_to_fit();
  std::vector<uint32_t> pending;
  for (uint32_t k = 0; k < links_.size(); ++k)
    if (links_[k].flags & kPending) pending.push_back(k);
  if (stopped()) {  // an interrupted solve: what was not traced carries nothing
    for (const uint32_t k : pending) links_[k].factor = 0, links_[k].flags &= ~kPending;
  } else {
    tbb::parallel_for(std::size_t(0), pending.size(), [&](std::size_t k) { transport(links_[pending[k]]); });
    transported_ += pending.size();
  }
  sort_links();
  refine_seconds_ += time.seconds();
  return split_count;
}

void HierarchicalSolver::sort_links() {
  std::sort(links_.begin(), links_.end(), [](const Link& a, const Link& b) {
    return a.receiver < b.receiver || (a.receiver == b.receiver && a.source < b.source);
  });
  link_start_.clear();
  receivers_.clear();
  for (uint32_t k = 0; k < links_.size(); ++k)
    if (k == 0 || links_[k].receiver != links_[k - 1].receiver) {
      link_start_.push_back(k);
      receivers_.push_back(links_[k].receiver);
    }
  link_start_.push_back(static_cast<uint32_t>(links_.size()));
}

void HierarchicalSolver::gather() {
  Stopwatch time;
  std::fill(gathered_.begin(), gathered_.end(), CornerIrradiance{});
  std::fill(cluster_in_.begin(), cluster_in_.end(), ShColor{});
  tbb::parallel_for(std::size_t(0), receivers_.size(), [&](std::size_t r) {
    const uint32_t receiver = receivers_[r];
    const bool to_cluster = tree_.nodes[receiver].is_cluster;
    CornerIrradiance irradiance{};
    ShColor incoming{};
    for (uint32_t k = link_start_[r]; k < link_start_[r + 1]; ++k) {
      const Link& link = links_[k];
      const HierarchyNode& source = tree_.nodes[link.source];
      if (!to_cluster && !source.is_cluster) {  // surface to surface: linear across the receiver
        const Color& b = radiosity_[link.source];
        for (std::size_t c = 0; c < 3; ++c) irradiance[c] += b * static_cast<double>(link.values[c]);
        continue;
      }
      const Vec3 w(link.values[0], link.values[1], link.values[2]);
      const Color from =
          source.is_cluster ? sh_evaluate(cluster_out_[source.payload], -w) : radiosity_[link.source];
      const Color arriving = from * static_cast<double>(link.factor);
      if (to_cluster) {
        add_delta(incoming, w, arriving);
      } else {
        for (Color& corner : irradiance) corner += arriving;
      }
    }
    if (to_cluster)
      cluster_in_[tree_.nodes[receiver].payload] = incoming;
    else
      gathered_[receiver] = irradiance;
  });
  gather_seconds_ += time.seconds();
}

// Parents before children: each surface's irradiance from its ancestors plus its own links; a
// cluster's incoming radiance to a surface root by the root's cosine.
void HierarchicalSolver::push() {
  for (uint32_t i = 0; i < tree_.nodes.size(); ++i) {
    const HierarchyNode& node = tree_.nodes[i];
    const bool under_cluster = node.parent != kNoNode && tree_.nodes[node.parent].is_cluster;
    if (node.is_cluster) {
      ShColor total = cluster_in_[node.payload];
      if (under_cluster) {
        const ShColor& above = cluster_down_[tree_.nodes[node.parent].payload];
        for (std::size_t k = 0; k < 9; ++k) total[k] += above[k];
      }
      cluster_down_[node.payload] = total;
      continue;
    }
    CornerIrradiance above{};
    if (under_cluster) {
      const Color from_cluster =
          sh_irradiance(cluster_down_[tree_.nodes[node.parent].payload], tree_.surface(i).normal);
      above = {from_cluster, from_cluster, from_cluster};
    } else if (node.parent != kNoNode) {
      // The parent's linear irradiance at this child's corners (RadiosityHierarchy::split's order:
      // the three corner triangles, then the middle one).
      const CornerIrradiance& p = down_[node.parent];
      const Color ab = (p[0] + p[1]) * 0.5, bc = (p[1] + p[2]) * 0.5, ca = (p[2] + p[0]) * 0.5;
      switch (i - tree_.nodes[node.parent].first_child) {
        case 0:
          above = {p[0], ab, ca};
          break;
        case 1:
          above = {ab, p[1], bc};
          break;
        case 2:
          above = {ca, bc, p[2]};
          break;
        default:
          above = {ab, bc, ca};
          break;
      }
    }
    for (std::size_t c = 0; c < 3; ++c) down_[i][c] = above[c] + gathered_[i][c];
  }
}

// B = E + first shot + ρ E at the leaves; returns the largest change of any channel, and in
// `largest` the largest reflected radiosity B − E (emitters, far brighter, would make any change
// look small).
double HierarchicalSolver::update_leaves(double& largest) {
  double change = 0;
  largest = 0;
  for (uint32_t i = 0; i < tree_.nodes.size(); ++i) {
    if (tree_.nodes[i].is_cluster || !tree_.is_leaf(i)) continue;
    const RadiositySurface& s = tree_.surface(i);
    const Color b = s.emission + s.first_shot + s.reflectance * leaf_irradiance(i);
    change = std::max(change, max(b - radiosity_[i], radiosity_[i] - b).max_component());
    largest = std::max(largest, (b - s.emission).max_component());
    radiosity_[i] = b;
  }
  return change;
}

// Children before parents: a surface's B is its children's area-weighted mean; a cluster's
// intensity Σ (B A / π) max(0, n·ω) over the surfaces under it, and its power Σ B A.
void HierarchicalSolver::pull() {
  for (uint32_t i = static_cast<uint32_t>(tree_.nodes.size()); i-- > 0;) {
    const HierarchyNode& node = tree_.nodes[i];
    if (node.is_cluster) {
      ShColor out{};
      Color power;
      for (uint32_t c = node.first_child; c < node.first_child + node.child_count; ++c) {
        const HierarchyNode& child = tree_.nodes[c];
        if (child.is_cluster) {
          for (std::size_t k = 0; k < 9; ++k) out[k] += cluster_out_[child.payload][k];
          power += cluster_power_[child.payload];
        } else {
          add_clamped_cosine(out, tree_.surface(c).normal, radiosity_[c] * (child.area / kPi));
          power += radiosity_[c] * child.area;
        }
      }
      cluster_out_[node.payload] = out;
      cluster_power_[node.payload] = power;
      continue;
    }
    if (node.child_count == 0) continue;
    Color sum;
    for (uint32_t c = node.first_child; c < node.first_child + node.child_count; ++c)
      sum += radiosity_[c] * tree_.nodes[c].area;
    radiosity_[i] = sum / node.area;
  }
}

// Each leaf's Σ F (the irradiance it would gather with B = 1 everywhere): 1 in a closed scene, ≈ 0
// for a leaf that sees nothing.
std::vector<double> HierarchicalSolver::row_sums() {
  const std::vector<Color> saved = radiosity_;
  for (uint32_t i = 0; i < tree_.nodes.size(); ++i)
    if (!tree_.nodes[i].is_cluster && tree_.is_leaf(i)) radiosity_[i] = Color(1);
  pull();
  gather();
  push();
  std::vector<double> sums(tree_.nodes.size());
  for (uint32_t i = 0; i < tree_.nodes.size(); ++i)
    sums[i] = tree_.nodes[i].is_cluster ? 0 : leaf_irradiance(i).r;
  radiosity_ = saved;
  pull();
  return sums;
}

RadiositySolveResult HierarchicalSolver::result(const std::vector<double>& sums) const {
  std::vector<RadiositySurface> patches, elements;
  std::vector<uint32_t> first{0};
  std::vector<std::array<Vec3, 3>> object_corners;
  std::vector<std::array<Vec2, 3>> uvs;
  std::vector<Color> element_radiosity;
  std::vector<uint8_t> hidden;
  std::vector<uint32_t> stack;
  for (const uint32_t root : tree_.root_of_input) {
    RadiositySurface patch = tree_.surface(root);
    Color first_shot;
    stack.assign(1, root);
    while (!stack.empty()) {
      const uint32_t node = stack.back();
      stack.pop_back();
      const HierarchyNode& n = tree_.nodes[node];
      if (n.child_count > 0) {
        for (uint32_t c = n.first_child + n.child_count; c-- > n.first_child;) stack.push_back(c);
        continue;
      }
      const HierarchySurface& leaf = tree_.surfaces[n.payload];
      elements.push_back(leaf.surface);
      object_corners.push_back(leaf.object_corners);
      uvs.push_back(leaf.uvs);
      element_radiosity.push_back(radiosity_[node]);
      hidden.push_back(!sums.empty() && sums[node] < kHiddenRowSum ? 1 : 0);
      first_shot += leaf.surface.first_shot * leaf.surface.area;
    }
    patch.first_shot = first_shot / patch.area;
    patches.push_back(patch);
    first.push_back(static_cast<uint32_t>(elements.size()));
  }
  RadiositySolveResult out;
  out.mesh = assemble_radiosity_mesh(std::move(patches), std::move(elements), std::move(first),
                                     std::move(object_corners), std::move(uvs), scene_.primitives.size());
  out.element_radiosity = std::move(element_radiosity);
  out.element_hidden = std::move(hidden);
  return out;
}

RadiositySolveResult HierarchicalSolver::solve() {
  Stopwatch solve_time;
  // The power the scene emits and reflects first (before any split: each input triangle's own
  // samples), which the tolerance is a fraction of; every node starts at B = E + first shot.
  compute_direct(tree_.root_of_input);
  grow_state();
  double power = 0;
  for (const uint32_t root : tree_.root_of_input)
    power += radiosity_[root].max_component() * tree_.nodes[root].area;
  epsilon_ = settings_.refinement_tolerance * power;
  relative_tolerance_ = std::min(kRelativeTolerancePerPowerTolerance * settings_.refinement_tolerance, 0.5);
  split_for_direct_light();
  double largest = 0;
  update_leaves(largest);  // B = E + first shot
  pull();
  links_.push_back({tree_.root(), tree_.root()});
  const bool several_clusters = !tree_.clusters.empty();
  if (!several_clusters) links_.clear();  // one triangle sees nothing of itself
  std::size_t splits = refine(several_clusters ? std::vector<uint32_t>{0} : std::vector<uint32_t>{});
  first_round_ = false;
  ProgressReporter progress("radiosity", 1000, "per mille of convergence", options_.quiet);
  std::size_t steps = 0;
  bool converged = false;
  double change_fraction = 0;
  for (;;) {
    ++rounds_;
    // Jacobi over the links until no leaf changes by more than the threshold.
    converged = false;
    double previous_change = 0;
    for (; steps < static_cast<std::size_t>(settings_.max_steps) && !stopped();) {
      gather();
      push();
      const double change = update_leaves(largest);
      pull();
      ++steps;
      change_fraction = largest > 0 ? change / largest : 0;
      // The convergence log: the solution after every iteration (one process).
      if (options_.on_step && !(options_.cluster && options_.cluster->distributed())) {
        RadiositySolveResult so_far = result({});
        so_far.steps = steps;
        options_.on_step(so_far);
      }
      progress.set_detail(fmt::format("change {:.3g}% after {} iterations, {} links", 100 * change_fraction,
                                      steps, links_.size()));
      progress.advance_to(
          static_cast<uint64_t>(1000 * convergence_progress(change_fraction, settings_.threshold)));
      // Jacobi's error falls geometrically, by q = this change / the last one, so what remains
      // beyond this iteration is about change · q / (1 − q) (ρ 0.95: twenty times the last
      // change): stop when that is within the threshold too.
      const double ratio = previous_change > 0 ? std::min(change / previous_change, 0.999) : 0.999;
      previous_change = change;
      const double remaining = change_fraction * std::max(1.0, ratio / (1 - ratio));
      if (remaining <= settings_.threshold) {
        converged = true;
        break;
      }
    }
    if (!converged || rounds_ >= kMaxRefinementRounds || stopped() || memory_stopped_) break;
    // Refine again with the radiosities solved (Hanrahan et al.: the oracle reads B).
    std::vector<uint32_t> all(links_.size());
    for (uint32_t k = 0; k < all.size(); ++k) all[k] = k;
    const std::size_t before = tree_.nodes.size();
    splits = refine(std::move(all));
    split_for_direct_light();
    if (splits == 0 && tree_.nodes.size() == before) break;
  }
  progress.finish();
  const std::vector<double> sums = row_sums();
  // What the result does not need goes before it is assembled (the peak of a million triangles).
  const std::size_t link_count = links_.size(), link_bytes = links_.capacity() * sizeof(Link);
  const double memory = static_cast<double>(tree_.memory_bytes() + link_bytes) / 1048576.0;
  occluders_.reset();
  for (auto* state : {&gathered_, &down_}) std::vector<CornerIrradiance>().swap(*state);
  for (auto* state : {&cluster_out_, &cluster_in_, &cluster_down_}) std::vector<ShColor>().swap(*state);
  std::vector<Link>().swap(links_);
  RadiositySolveResult out = result(sums);
  out.steps = steps;
  out.converged = converged;
  out.unshot_fraction = 0;
  out.form_factors = links_made_;
  out.form_factor_rows = 0;
  out.form_factor_bytes = link_bytes;
  out.solve_seconds = solve_time.seconds();
  if (options_.facts) {
    std::size_t leaves = 0, max_depth = 0;
    for (const HierarchyNode& node : tree_.nodes)
      if (!node.is_cluster) {
        leaves += node.child_count == 0 ? 1 : 0;
        max_depth = std::max<std::size_t>(max_depth, node.depth);
      }
    std::vector<double> leaf_sums;
    for (uint32_t i = 0; i < tree_.nodes.size(); ++i)
      if (!tree_.nodes[i].is_cluster && tree_.is_leaf(i)) leaf_sums.push_back(sums[i]);
    nlohmann::json& facts = *options_.facts;
    facts = {{"solver", "hierarchical"},
             {"input_triangles", tree_.root_of_input.size()},
             {"patches", out.mesh.patches.size()},
             {"elements", out.mesh.elements.size()},
             {"leaves", leaves},
             {"nodes", tree_.nodes.size()},
             {"clusters", tree_.clusters.size()},
             {"levels", max_depth + 1},
             {"links", link_count},
             {"links_evaluated", links_made_},
             {"visibility_rays", (surface_links_made_ + transported_) * kVisibilityRays},
             {"refinement_rounds", rounds_},
             {"refinement_tolerance", settings_.refinement_tolerance},
             {"min_element_size", min_edge_},
             {"steps", steps},
             {"converged", converged},
             {"change_fraction", change_fraction},
             {"memory_mib", memory},
             {"refinement_stopped_by_memory", memory_stopped_},
             {"solve_seconds", out.solve_seconds},
             {"refine_seconds", refine_seconds_},
             {"form_factors_per_second",
              refine_seconds_ > 0 ? static_cast<double>(links_made_) / refine_seconds_ : 0.0},
             {"first_shot_seconds", direct_seconds_},
             {"gather_seconds", gather_seconds_},
             {"scene_lights", scene_.lights.size()},
             {"row_sum", row_sum_facts(leaf_sums)}};
    if (cancel_requested()) {
      facts["interrupted"] = true;
      facts["completed"] = fmt::format("{} iterations, change {:.3g}%", steps, 100 * change_fraction);
    }
  }
  return out;
}

}  // namespace

RadiositySolveResult solve_hierarchical_radiosity(const Scene& scene, const RadiositySettings& settings,
                                                  const RadiositySolveOptions& options) {
  Stopwatch mesh_time;
  RadiosityMeshSettings mesh_settings;
  // Curved shapes by chord error (SPEC §10.1): a small far sphere gets a few dozen
  // triangles, a large near one up to kChordSegmentsPerSegment × segments.
  mesh_settings.segments = kChordSegmentsPerSegment * settings.segments;
  mesh_settings.chord_fraction = kChordFraction;
  RadiosityInput input = radiosity_input(scene, mesh_settings);
  if (settings.split_at_contacts) {
    // The leak remedy (SPEC §10): input triangles cut where other objects meet them, after halving
    // them to patch_size so that a cut runs across one piece, not the whole of a wall.
    const double patch_size = settings.patch_size > 0 ? settings.patch_size : input.scene_size / 8;
    input = split_input_at_contacts(scene, input, patch_size);
  }
  // Refused before the hierarchy is built: its roots and clusters alone (links and leaves grow
  // within the limit as they are refined, and refinement stops at it).
  const double least = static_cast<double>(input.triangles.size()) *
                       (2.0 * sizeof(HierarchyNode) + sizeof(HierarchySurface) + sizeof(HierarchyCluster) +
                        3 * sizeof(ShColor) + 4 * sizeof(Color));
  check_form_factor_memory(static_cast<uint64_t>(std::min(least, 1.8e19)), settings,
                           fmt::format("the hierarchy of {} input triangles", input.triangles.size()),
                           "lower radiosity.segments, or simplify the scene's meshes");
  if (input.triangles.empty())
    throw std::invalid_argument("radiosity mesh: the scene has no surface to mesh");
  RadiosityHierarchy hierarchy(scene, input);
  TriangleMesh visible_surfaces;  // what visibility rays are traced against
  for (const CornerTriangle& triangle : input.triangles) {
    const auto first = static_cast<uint32_t>(visible_surfaces.positions.size());
    for (const MeshCorner& corner : triangle) visible_surfaces.positions.push_back(corner.position);
    visible_surfaces.triangles.push_back({first, first + 1, first + 2});
  }
  auto occluders = std::make_unique<TriangleOccluders>(visible_surfaces);
  visible_surfaces = TriangleMesh();
  const double mesh_seconds = mesh_time.seconds();
  HierarchicalSolver solver(scene, settings, options, hierarchy, std::move(occluders));
  RadiositySolveResult result = solver.solve();
  result.mesh_seconds = mesh_seconds;
  if (options.facts) (*options.facts)["mesh_seconds"] = mesh_seconds;
  return result;
}

}  // namespace candela
