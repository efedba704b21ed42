// Tests of the meshless sites and bases (seed 002 §3.3, §4.1–4.2, §5.2.2; SPEC §11).
#include "meshless/meshless_basis.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "math/constants.h"
#include "math/pcg32.h"
#include "meshless/site_sampling.h"

namespace candela {
namespace {

TEST(SiteDistance, StretchesTheEuclideanDistanceAsNormalsTurnApart) {
  const Site p{{0, 0, 0}, {0, 0, 1}};
  EXPECT_DOUBLE_EQ(site_distance(p, {{3, 4, 0}, {0, 0, 1}}), 5);                       // same normal
  EXPECT_NEAR(site_distance(p, {{3, 4, 0}, {0, std::sin(kPi / 3), 0.5}}), 10, 1e-12);  // 60°: ×2
  EXPECT_TRUE(std::isinf(site_distance(p, {{3, 4, 0}, {0, 1, 0}})));                   // 90°
  EXPECT_TRUE(std::isinf(site_distance(p, {{0, 0, 0}, {0, 0, -1}})));                  // opposite
  EXPECT_EQ(site_distance(p, p), 0);
  // Never below the Euclidean distance, and symmetric.
  const Site q{{1, 2, 3}, normalize(Vec3{1, 1, 1})};
  EXPECT_GE(site_distance(p, q), length(q.position));
  EXPECT_EQ(site_distance(p, q), site_distance(q, p));
}

// Sites on a jittered n × n lattice over [0, 1]² (z = 0, normal +z), and on the unit sphere
// (Fibonacci points, outward normals), with radii from their m nearest neighbours.
SiteSet plane_sites(int n, uint64_t seed) {
  SiteSet set;
  Pcg32 random(seed, 1);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      set.sites.push_back(
          {{(i + 0.25 + 0.5 * random.next_double()) / n, (j + 0.25 + 0.5 * random.next_double()) / n, 0},
           {0, 0, 1}});
  assign_radii(set, 10);
  return set;
}

SiteSet sphere_sites(int count) {
  SiteSet set;
  const double golden = kPi * (3 - std::sqrt(5.0));
  for (int k = 0; k < count; ++k) {
    const double z = 1 - (k + 0.5) * 2.0 / count, r = std::sqrt(1 - z * z), phi = golden * k;
    const Vec3 p{r * std::cos(phi), r * std::sin(phi), z};
    set.sites.push_back({p, p});
  }
  assign_radii(set, 10);
  return set;
}

TEST(SiteRadii, AreTheSiteDistanceOfTheMthNearestNeighbour) {
  const SiteSet set = plane_sites(12, 3);
  for (std::size_t i = 0; i < set.sites.size(); ++i) {
    std::vector<double> distances;
    for (std::size_t j = 0; j < set.sites.size(); ++j)
      if (j != i) distances.push_back(site_distance(set.sites[i], set.sites[j]));
    std::sort(distances.begin(), distances.end());
    EXPECT_EQ(set.radius[i], distances[9]) << i;                                      // brute force, m = 10
    EXPECT_DOUBLE_EQ(set.effective_area[i], kPi * distances[9] * distances[9] / 11);  // 002 eq. 5.5
  }
}

// 002 eq. 5.4: for a partition of unity the effective areas add up to the surface's area; eq. 5.5
// approximates them (to 10 % here).
TEST(SiteRadii, EffectiveAreasSumToTheSurfaceArea) {
  double plane = 0, sphere = 0;
  for (const double a : plane_sites(80, 5).effective_area) plane += a;
  for (const double a : sphere_sites(4000).effective_area) sphere += a;
  RecordProperty("plane_ratio", std::to_string(plane / 1));
  RecordProperty("sphere_ratio", std::to_string(sphere / (4 * kPi)));
  EXPECT_NEAR(plane, 1, 0.1);
  EXPECT_NEAR(sphere, 4 * kPi, 0.1 * 4 * kPi);
}

TEST(MeshlessBasis, PartitionsOfUnitySumToOneAtRandomSites) {
  for (const SiteSet& set : {plane_sites(20, 7), sphere_sites(600)}) {
    const MeshlessBasis normalized(set.sites, set.radius, BasisKind::normalized);
    const MeshlessBasis shepard(set.sites, set.radius, BasisKind::shepard);
    Pcg32 random(11, 2);
    const bool on_plane = set.sites.front().normal.z == 1;
    for (int k = 0; k < 500; ++k) {
      Site p;
      if (on_plane) {
        p = {{0.05 + 0.9 * random.next_double(), 0.05 + 0.9 * random.next_double(), 0}, {0, 0, 1}};
      } else {
        const double z = 2 * random.next_double() - 1, phi = 2 * kPi * random.next_double(),
                     r = std::sqrt(1 - z * z);
        const Vec3 q{r * std::cos(phi), r * std::sin(phi), z};
        p = {q, q};
      }
      EXPECT_NEAR(normalized.sum(p), 1, 1e-12);
      EXPECT_NEAR(shepard.sum(p), 1, 1e-12);
    }
  }
}

// The radial basis is normalised — a partition of unity like the other two — where
// the thesis's Gaussians sum to about 1.4 on evenly spread sites (which made a furnace 43–46 %
// too bright); both kernels.
TEST(MeshlessBasis, RadialBasisIsAPartitionOfUnity) {
  const SiteSet set = plane_sites(30, 13);
  for (const RadialKernel kernel : {RadialKernel::gaussian, RadialKernel::cubic}) {
    const MeshlessBasis radial(set.sites, set.radius, BasisKind::radial, kernel);
    Pcg32 random(17, 3);
    for (int k = 0; k < 200; ++k) {
      const Site p{{0.2 + 0.6 * random.next_double(), 0.2 + 0.6 * random.next_double(), 0}, {0, 0, 1}};
      EXPECT_NEAR(radial.sum(p), 1, 1e-12);
    }
  }
}

TEST(MeshlessBasis, ShepardInterpolatesItsCentres) {
  const SiteSet set = plane_sites(10, 9);
  const MeshlessBasis shepard(set.sites, set.radius, BasisKind::shepard);
  std::vector<std::pair<uint32_t, double>> weights;
  for (uint32_t i = 0; i < set.sites.size(); ++i) {
    shepard.evaluate(set.sites[i], weights);
    ASSERT_EQ(weights.size(), 1u);
    EXPECT_EQ(weights[0].first, i);
    EXPECT_EQ(weights[0].second, 1.0);
  }
  // Between centres it blends: more than one element, each below 1, continuous at the support's
  // edge (a point just inside the edge of element 0's support gets a tiny weight from it).
  const Site between{(set.sites[0].position + set.sites[1].position) * 0.5, {0, 0, 1}};
  shepard.evaluate(between, weights);
  EXPECT_GT(weights.size(), 1u);
  for (const auto& [i, w] : weights) EXPECT_LT(w, 1.0);
}

TEST(MeshlessBasis, RadialKernelsHaveTheSeedsShape) {
  // 002 eq. 4.8: K(0) = 1, K(1/2) = 1/2, K(1) = 0, decreasing.
  EXPECT_EQ(cubic_kernel(0), 1);
  EXPECT_DOUBLE_EQ(cubic_kernel(0.5), 0.5);
  EXPECT_EQ(cubic_kernel(1), 0);
  EXPECT_EQ(cubic_kernel(2), 0);
  const std::vector<Site> sites{{{0, 0, 0}, {0, 0, 1}}, {{10, 0, 0}, {0, 0, 1}}};
  const std::vector<double> radii{1, 1};
  const MeshlessBasis gaussian(sites, radii, BasisKind::radial, RadialKernel::gaussian);
  std::vector<std::pair<uint32_t, double>> weights;
  // Alone, an element is 1 over its support (normalised) and nothing past 4 r_0 = r.
  gaussian.evaluate({{0.5, 0, 0}, {0, 0, 1}}, weights);
  ASSERT_EQ(weights.size(), 1u);
  EXPECT_DOUBLE_EQ(weights[0].second, 1.0);
  gaussian.evaluate({{1.01, 0, 0}, {0, 0, 1}}, weights);
  EXPECT_TRUE(weights.empty());
  // Two overlapping elements (centres 1 apart, radius 2) share a point in the ratio of the
  // kernels: at 0.25 and 0.75 from them, t = 1/8 and 3/8 of the radius.
  const std::vector<Site> pair{{{0, 0, 0}, {0, 0, 1}}, {{1, 0, 0}, {0, 0, 1}}};
  const std::vector<double> pair_radii{2, 2};
  const auto ratio = [&](const MeshlessBasis& basis, const Site& p) {
    basis.evaluate(p, weights);
    EXPECT_EQ(weights.size(), 2u);
    EXPECT_NEAR(weights[0].second + weights[1].second, 1, 1e-12);
    return weights.size() == 2 ? weights[0].second / weights[1].second : 0.0;
  };
  // 002 eq. 4.7 with r_0 = r/4: exp(−8t²), so exp(−1/8)/exp(−9/8) = e.
  const MeshlessBasis pair_gaussian(pair, pair_radii, BasisKind::radial, RadialKernel::gaussian);
  EXPECT_NEAR(ratio(pair_gaussian, {{0.25, 0, 0}, {0, 0, 1}}), std::exp(1.0), 1e-12);
  const MeshlessBasis pair_cubic(pair, pair_radii, BasisKind::radial, RadialKernel::cubic);
  EXPECT_NEAR(ratio(pair_cubic, {{0.25, 0, 0}, {0, 0, 1}}), cubic_kernel(0.125) / cubic_kernel(0.375), 1e-12);
  // The site distance, not the Euclidean one: a normal 60° away doubles both distances, t = 1/4
  // and 3/4: exp(−1/2)/exp(−9/2) = e⁴.
  EXPECT_NEAR(ratio(pair_gaussian, {{0.25, 0, 0}, {0, std::sin(kPi / 3), 0.5}}), std::exp(4.0), 1e-9);
  // Uncovered: nothing (the partitions of unity have nothing to normalise).
  const MeshlessBasis normalized(sites, radii, BasisKind::normalized);
  normalized.evaluate({{5, 0, 0}, {0, 0, 1}}, weights);
  EXPECT_TRUE(weights.empty());
  // Facing away: the normalized basis's max(0, p⃗·p⃗_j) factor.
  normalized.evaluate({{0.2, 0, 0}, {0, 0, -1}}, weights);
  EXPECT_TRUE(weights.empty());
  EXPECT_THROW(MeshlessBasis(sites, std::vector<double>{1}, BasisKind::radial), std::invalid_argument);
  EXPECT_THROW(MeshlessBasis(sites, std::vector<double>{1, 0}, BasisKind::radial), std::invalid_argument);
}

}  // namespace
}  // namespace candela
