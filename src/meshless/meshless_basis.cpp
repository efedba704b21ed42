#include "meshless/meshless_basis.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace candela {

MeshlessBasis::MeshlessBasis(const std::vector<Site>& sites, const std::vector<double>& radii, BasisKind kind,
                             RadialKernel kernel, double shepard_power)
    : sites_(sites), radii_(radii), kind_(kind), kernel_(kernel), shepard_power_(shepard_power) {
  if (radii.size() != sites.size())
    throw std::invalid_argument("meshless basis: " + std::to_string(radii.size()) + " radii for " +
                                std::to_string(sites.size()) + " sites");
  if (!(shepard_power >= 0)) throw std::invalid_argument("meshless basis: the Shepard power must be >= 0");
  for (uint32_t i = 0; i < radii.size(); ++i) {
    if (!(radii[i] > 0))
      throw std::invalid_argument("meshless basis: radius " + std::to_string(i) + " is not > 0");
    if (std::isinf(radii[i])) unbounded_.push_back(i);
  }
  // The Euclidean search reaches as far as the largest support but a few: a handful of isolated
  // sites (on the back of a lamp, say) with supports of metres would otherwise make every lookup
  // gather hundreds of candidates (a scene 40 times slower). The widest 1 % are candidates
  // everywhere instead, like the unbounded ones.
  std::vector<double> finite;
  for (const double r : radii)
    if (std::isfinite(r)) finite.push_back(r);
  double largest_radius = 0;
  if (!finite.empty()) {
    const std::size_t kept = finite.size() - finite.size() / 100 - 1;
    std::nth_element(finite.begin(), finite.begin() + static_cast<std::ptrdiff_t>(kept), finite.end());
    largest_radius = finite[kept];
    for (uint32_t i = 0; i < radii.size(); ++i)
      if (std::isfinite(radii[i]) && radii[i] > largest_radius) unbounded_.push_back(i);
  }
  std::sort(unbounded_.begin(), unbounded_.end());
  std::vector<uint8_t> is_unbounded(radii.size(), 0);
  for (const uint32_t i : unbounded_) is_unbounded[i] = 1;
  // Classes down from the largest radius, each 1.3 times narrower than the one above; at most 16
  // (the last takes every smaller radius).
  constexpr double kClassRatio = 1.3;
  constexpr int kMaxClasses = 16;
  std::vector<std::vector<uint32_t>> members(kMaxClasses);
  for (uint32_t i = 0; i < radii.size(); ++i) {
    if (is_unbounded[i]) continue;
    const int k = static_cast<int>(std::floor(std::log(largest_radius / radii[i]) / std::log(kClassRatio)));
    members[static_cast<std::size_t>(std::clamp(k, 0, kMaxClasses - 1))].push_back(i);
  }
  for (auto& list : members) {
    if (list.empty()) continue;
    RadiusClass& added = classes_.emplace_back();
    added.members = std::move(list);
    for (const uint32_t i : added.members) {
      added.sites.push_back(sites[i]);
      added.reach = std::max(added.reach, radii[i]);
    }
  }
  // Each class's sites stay where they are now (the index refers to them).
  for (RadiusClass& c : classes_) c.index = std::make_unique<SiteIndex>(c.sites);
}

void MeshlessBasis::evaluate(const Site& p, std::vector<std::pair<uint32_t, double>>& weights) const {
  weights.clear();
  // Every element whose support can reach p lies within its class's largest support in Euclidean
  // terms (the site distance is never below the Euclidean one; every basis's support is r_i, 002
  // eq. 4.5). The candidates in increasing index, then the unbounded ones: the order the weights
  // are added in.
  thread_local std::vector<uint32_t> candidates, found;
  candidates.clear();
  for (const RadiusClass& c : classes_) {
    found.clear();
    c.index->within_euclidean(p.position, c.reach, found);
    for (const uint32_t k : found) candidates.push_back(c.members[k]);
  }
  if (classes_.size() > 1) std::sort(candidates.begin(), candidates.end());
  candidates.insert(candidates.end(), unbounded_.begin(), unbounded_.end());
  double total = 0;
  for (const uint32_t i : candidates) {
    const Site& centre = sites_[i];
    const double r = radii_[i];
    double value = 0;
    switch (kind_) {
      case BasisKind::radial: {
        const double t = site_distance(p, centre) / r;
        // 002 eq. 4.7 with r_0 = r_i / 4 (see the header): exp(−½(4t)²), cut at t = 1.
        if (kernel_ == RadialKernel::gaussian)
          value = t < 1 ? std::exp(-8 * t * t) : 0.0;
        else
          value = cubic_kernel(t);
        break;
      }
      case BasisKind::normalized: {  // 002 eq. 4.9
        // Most candidates lie outside their support: they are passed by before the square root
        // and the division (a hair beyond r² so that rounding cannot drop one K would keep).
        const double d2 = length_squared(p.position - centre.position);
        if (d2 > r * r * (1 + 1e-12)) break;
        value = cubic_kernel(std::sqrt(d2) / r) * std::max(0.0, dot(p.normal, centre.normal));
        break;
      }
      case BasisKind::shepard: {  // 002 eqs. 4.10–4.11, Franke–Little weights
        const double d = site_distance(p, centre);
        if (!(d < r)) break;
        if (d == 0) {
          // At a centre the weight is infinite: φ = 1 there (ties between coincident centres
          // share it).
          value = std::numeric_limits<double>::infinity();
          break;
        }
        value = std::isinf(r) ? std::pow(d, -shepard_power_) : std::pow((r - d) / (r * d), shepard_power_);
        break;
      }
    }
    if (value > 0) {
      weights.emplace_back(i, value);
      total += value;
    }
  }
  // In increasing i (the search returns them in its own order): sorting the few non-zero weights
  // costs less than sorting the candidates.
  std::sort(weights.begin(), weights.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  if (weights.empty()) return;
  if (std::isinf(total)) {
    // Shepard at a centre: the infinite weights share 1, the rest get 0.
    std::size_t at_centre = 0;
    for (const auto& [i, value] : weights) at_centre += std::isinf(value);
    std::erase_if(weights, [](const auto& entry) { return !std::isinf(entry.second); });
    for (auto& entry : weights) entry.second = 1.0 / static_cast<double>(at_centre);
    return;
  }
  for (auto& entry : weights) entry.second /= total;
}

double MeshlessBasis::sum(const Site& p) const {
  std::vector<std::pair<uint32_t, double>> weights;
  evaluate(p, weights);
  double total = 0;
  for (const auto& [i, value] : weights) total += value;
  return total;
}

}  // namespace candela
