// The hierarchical meshless basis (meshless/site_hierarchy.h) and the hierarchical
// transport (meshless/transfer_matrix.h) of Lehtinen et al. 2008.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <string>

#include "closed_cube.h"
#include "integrators/meshless_method.h"
#include "integrators/scene_loading.h"
#include "math/pcg32.h"
#include "meshless/meshless_basis.h"
#include "meshless/site_hierarchy.h"
#include "meshless/site_sampling.h"
#include "meshless/transfer_matrix.h"
#include "render_support.h"
#include "util/error.h"

namespace candela {
namespace {

// Sites on a jittered side × side lattice over the unit square z = 0, facing +z, Δ = the lattice step.
SiteSet square_of_sites(int side, uint64_t seed = 7) {
  SiteSet set;
  const double step = 1.0 / side;
  Pcg32 random(seed, 1);
  for (int y = 0; y < side; ++y)
    for (int x = 0; x < side; ++x) {
      const double jitter_x = (random.next_double() - 0.5) * 0.2 * step,
                   jitter_y = (random.next_double() - 0.5) * 0.2 * step;
      set.sites.push_back({Vec3{(x + 0.5) * step + jitter_x, (y + 0.5) * step + jitter_y, 0}, Vec3{0, 0, 1}});
    }
  set.spacing = 0.8 * step;  // no two closer than the jittered lattice allows
  assign_radii(set, 10);
  return set;
}

TEST(SiteHierarchy, LevelsNestThinAsPoissonDiscsAndEndSmall) {
  const SiteSet set = square_of_sites(48);
  const SiteHierarchy hierarchy(set, 10);
  ASSERT_GE(hierarchy.level_count(), 4u);
  EXPECT_EQ(hierarchy.level_sites(0).size(), set.sites.size());
  EXPECT_LE(hierarchy.level_sites(hierarchy.level_count() - 1).size(), 16u);
  for (std::size_t l = 0; l + 1 < hierarchy.level_count(); ++l) {
    const auto finer = hierarchy.level_sites(l), coarser = hierarchy.level_sites(l + 1);
    const std::set<uint32_t> finer_set(finer.begin(), finer.end());
    for (const uint32_t site : coarser) EXPECT_TRUE(finer_set.count(site)) << "level " << l + 1;
    EXPECT_TRUE(std::is_sorted(coarser.begin(), coarser.end()));
    // About a quarter as dense on a surface when the spacing doubles (a Poisson-disc set).
    const double ratio = static_cast<double>(finer.size()) / static_cast<double>(coarser.size());
    if (coarser.size() > 30) {
      EXPECT_GT(ratio, 2.2) << "level " << l + 1;
      EXPECT_LT(ratio, 6.0) << "level " << l + 1;
    }
    const double spacing = hierarchy.level_spacing(l + 1);
    EXPECT_DOUBLE_EQ(spacing, set.spacing * std::pow(2.0, static_cast<double>(l + 1)));  // each shrinks
    // No two closer than the level's spacing, and every finer site within it of a coarser one.
    for (std::size_t a = 0; a < coarser.size(); ++a)
      for (std::size_t b = a + 1; b < coarser.size(); ++b)
        EXPECT_GE(site_distance(set.sites[coarser[a]], set.sites[coarser[b]]), spacing);
    for (const uint32_t site : finer) {
      double nearest = INFINITY;
      for (const uint32_t c : coarser)
        nearest = std::min(nearest, site_distance(set.sites[site], set.sites[c]));
      EXPECT_LT(nearest, spacing) << "site " << site << " level " << l;
    }
  }
}

TEST(SiteHierarchy, EveryLevelIsAPartitionOfUnity) {
  const SiteSet set = square_of_sites(40);
  const SiteHierarchy hierarchy(set, 10);
  Pcg32 random(3, 4);
  for (int k = 0; k < 200; ++k) {
    const Site p{Vec3{random.next_double(), random.next_double(), 0}, Vec3{0, 0, 1}};
    for (std::size_t l = 0; l < hierarchy.level_count(); ++l)
      ASSERT_NEAR(hierarchy.level_basis(l).sum(p), 1.0, 1e-12) << "level " << l;
    // All levels together: one per level.
    std::vector<std::pair<uint32_t, double>> weights;
    hierarchy.evaluate(p, weights);
    double total = 0;
    for (const auto& [node, value] : weights) total += value;
    EXPECT_NEAR(total, static_cast<double>(hierarchy.level_count()), 1e-10);
    EXPECT_TRUE(std::is_sorted(weights.begin(), weights.end()));
  }
}

TEST(SiteHierarchy, TheTreeLinksEverySiteToTheNearestOfTheNextLevel) {
  const SiteSet set = square_of_sites(32);
  const SiteHierarchy hierarchy(set, 10);
  const std::size_t top = hierarchy.level_count() - 1;
  std::size_t counted = 0;
  for (uint32_t node = 0; node < hierarchy.node_count(); ++node) {
    const uint32_t level = hierarchy.node_level(node), parent = hierarchy.parent(node);
    if (node < set.sites.size()) {
      EXPECT_EQ(hierarchy.node_site(node), node);
    }
    if (level == top) {
      EXPECT_EQ(parent, UINT32_MAX);
      continue;
    }
    ASSERT_NE(parent, UINT32_MAX);
    EXPECT_EQ(hierarchy.node_level(parent), level + 1);
    EXPECT_LT(node, parent);  // children before parents
    const Site& site = set.sites[hierarchy.node_site(node)];
    const double to_parent = site_distance(site, set.sites[hierarchy.node_site(parent)]);
    for (const uint32_t other : hierarchy.level_sites(level + 1))
      EXPECT_LE(to_parent, site_distance(site, set.sites[other]) + 1e-15);
    // A site that is on the next level is its own parent.
    const auto next = hierarchy.level_sites(level + 1);
    if (std::find(next.begin(), next.end(), hierarchy.node_site(node)) != next.end()) {
      EXPECT_EQ(hierarchy.node_site(parent), hierarchy.node_site(node));
    }
    const auto siblings = hierarchy.children(parent);
    EXPECT_NE(std::find(siblings.begin(), siblings.end(), node), siblings.end());
    ++counted;
  }
  std::size_t children = 0;
  for (uint32_t node = 0; node < hierarchy.node_count(); ++node) children += hierarchy.children(node).size();
  EXPECT_EQ(children, counted);
}

TEST(SiteHierarchy, LevelZeroAloneIsTheFlatNormalizedBasis) {
  const SiteSet set = square_of_sites(30);
  const SiteHierarchy hierarchy(set, 10);
  const MeshlessBasis flat(set.sites, set.radius, BasisKind::normalized);
  std::vector<Color> values(set.sites.size()), coefficients(hierarchy.node_count());
  for (std::size_t i = 0; i < values.size(); ++i) {
    const Vec3 p = set.sites[i].position;
    values[i] = Color(std::sin(7 * p.x) + 2, p.y * p.y, 1);
    coefficients[i] = values[i];  // level 0's nodes are the sites; every coarser one 0
  }
  Pcg32 random(5, 6);
  std::vector<std::pair<uint32_t, double>> weights;
  for (int k = 0; k < 100; ++k) {
    const Site p{Vec3{random.next_double(), random.next_double(), 0}, Vec3{0, 0, 1}};
    flat.evaluate(p, weights);
    Color expected;
    for (const auto& [i, phi] : weights) expected += values[i] * phi;
    const Color got = hierarchy.reconstruct(p, coefficients);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], expected[c], 1e-12);
  }
}

TEST(SiteHierarchy, ProjectionPutsSmoothLightOnTheCoarseLevels) {
  const SiteSet set = square_of_sites(48);
  const SiteHierarchy hierarchy(set, 10);
  const std::size_t n = set.sites.size();
  // A constant: the coarsest level holds it all, every finer coefficient is 0.
  const std::vector<Color> constant(n, Color(0.25, 0.5, 2));
  const std::vector<Color> flat_coefficients = hierarchy.project(constant);
  for (uint32_t node = 0; node < hierarchy.node_count(); ++node) {
    const bool top = hierarchy.node_level(node) + 1 == hierarchy.level_count();
    for (int c = 0; c < 3; ++c)
      ASSERT_NEAR(flat_coefficients[node][c], top ? constant[0][c] : 0.0, 1e-12) << "node " << node;
  }
  // A smooth ramp: reconstructed at the sites within 2 % of its range, and the finest level's
  // details (3/4 of the coefficients) mostly near zero — what makes the representation sparse.
  std::vector<Color> ramp(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 p = set.sites[i].position;
    ramp[i] = Color(1 + p.x + 0.5 * p.y);
  }
  const std::vector<Color> coefficients = hierarchy.project(ramp);
  std::vector<double> finest;
  for (std::size_t i = 0; i < n; ++i) {
    EXPECT_NEAR(hierarchy.reconstruct(set.sites[i], coefficients).r, ramp[i].r, 0.03) << "site " << i;
    finest.push_back(std::fabs(coefficients[i].r));
  }
  std::nth_element(finest.begin(), finest.begin() + static_cast<std::ptrdiff_t>(n / 2), finest.end());
  EXPECT_LT(finest[n / 2], 0.01);  // the median finest detail: under 1 % of the ramp's range 1.5
}

// A closed cube of glowing walls (the furnace), meshless settings as given.
std::unique_ptr<Scene> cube(double albedo, const std::string& meshless) {
  const std::string material = R"({"kd": )" + std::to_string(albedo) + R"(, "emission": 1})";
  return load_scene_text(R"({"format": "candela/1",
    "camera": {"eye": [1, 1.1, 1.7], "target": [0.9, 0.8, 0], "fov": 80, "width": 16, "height": 16},
    "render": {"method": "meshless"}, "meshless": )" +
                             meshless + ", " + testing::closed_cube_shapes(material) + "}",
                         "cube.json", ".");
}

MeshlessSolution solve(const Scene& scene) {
  return solve_meshless(scene, read_meshless_settings(scene.plugin_settings.node("meshless")));
}

// Per site, what S gathers from a radiosity of 1 everywhere: its own row and, with hierarchical
// transport, what the links of its coarser ancestors bring.
std::vector<double> row_sums(const TransferMatrix& matrix) {
  const std::vector<Color> ones(static_cast<std::size_t>(matrix.S.cols()), Color(1));
  std::vector<Color> pushed;
  matrix.pushed_values(ones, pushed);
  std::vector<double> sums;
  for (int32_t j = 0; j < matrix.S.rows(); ++j) {
    double sum = pushed[static_cast<std::size_t>(j)].g;
    for (Eigen::SparseMatrix<float, Eigen::RowMajor, int32_t>::InnerIterator e(matrix.S, j); e; ++e)
      sum += e.value();
    sums.push_back(sum);
  }
  return sums;
}

TEST(HierarchicalTransport, RefiningEverythingGivesTheFlatMatrixEntryForEntry) {
  const std::string common = R"("spacing": 0.25, "grid": 16, "rounds": 4, "gather_rays": 16)";
  const MeshlessSolution flat = solve(*cube(0.5, "{" + common + "}"));
  const MeshlessSolution all =
      solve(*cube(0.5, R"({"transport": "hierarchical", "cluster_angle": 0, )" + common + "}"));
  const auto& S = flat.matrix.S;
  ASSERT_GT(S.rows(), 100);
  ASSERT_EQ(all.matrix.S.rows(), S.rows());
  EXPECT_GT(all.matrix.S.cols(), S.cols());  // the hierarchy's nodes are columns
  EXPECT_EQ(all.matrix.cluster_links, 0u);
  ASSERT_EQ(all.matrix.entries(), flat.matrix.entries());
  for (int32_t j = 0; j < S.rows(); ++j) {
    Eigen::SparseMatrix<float, Eigen::RowMajor, int32_t>::InnerIterator a(S, j), b(all.matrix.S, j);
    for (; a && b; ++a, ++b) {
      ASSERT_EQ(a.col(), b.col()) << "row " << j;
      ASSERT_EQ(a.value(), b.value()) << "row " << j << " column " << a.col();
    }
    EXPECT_FALSE(a || b) << "row " << j;
  }
  for (std::size_t i = 0; i < flat.transfer.lambda.size(); ++i)
    ASSERT_EQ(flat.transfer.lambda[i].g, all.transfer.lambda[i].g);
}

TEST(HierarchicalTransport, FurnaceRowsSumToOneAndGiveEOverOneMinusRho) {
  for (const double albedo : {0.5, 0.9}) {
    const auto scene =
        cube(albedo, R"({"transport": "hierarchical", "spacing": 0.1, "grid": 32, "rounds": 6})");
    const MeshlessSolution solution = solve(*scene);
    ASSERT_GT(solution.matrix.cluster_links, 0u);
    ASSERT_GT(solution.matrix.receiver_links.nonZeros(), 0);  // clusters receive too
    const std::vector<double> sums = row_sums(solution.matrix);
    for (std::size_t j = 0; j < sums.size(); ++j) ASSERT_NEAR(sums[j], 1, 0.005) << "row " << j;
    const Film film = testing::render_scene(*scene, "meshless", 2);
    const double expected = 1 / (1 - albedo);
    for (const Color& pixel : film.pixels()) ASSERT_NEAR(pixel.g, expected, 0.02 * expected) << albedo;
  }
}

TEST(HierarchicalTransport, EntriesGrowSubQuadratically) {
  // The same closed cube at three densities: the flat matrix's entries grow as n² (every site sees
  // nearly every other), the hierarchy's as about n log n.
  std::vector<double> sites, entries;
  for (const double spacing : {0.2, 0.1, 0.05}) {
    const auto scene =
        cube(0.5, R"({"transport": "hierarchical", "gather_rays": 4, "grid": 48, "rounds": 8, "spacing": )" +
                      std::to_string(spacing) + "}");
    const MeshlessSolution solution = solve(*scene);
    sites.push_back(static_cast<double>(solution.matrix.S.rows()));
    entries.push_back(static_cast<double>(solution.matrix.entries()));
  }
  ASSERT_GT(sites.back(), 3 * sites.front());
  const double exponent = std::log(entries.back() / entries.front()) / std::log(sites.back() / sites.front());
  EXPECT_LT(exponent, 1.45) << sites.front() << " → " << sites.back() << " sites, " << entries.front()
                            << " → " << entries.back() << " entries";
  EXPECT_LT(entries.back(), 0.25 * sites.back() * sites.back());
}

// More links than the limit: refused naming the settings to change, before the rows are computed;
// the new settings are checked like the others.
TEST(HierarchicalTransport, TooManyLinksAndBadSettingsAreRefused) {
  const auto scene = cube(0.5, R"({"transport": "hierarchical", "spacing": 0.2, "grid": 16, "rounds": 4})");
  const MeshlessSettings settings = read_meshless_settings(scene->plugin_settings.node("meshless"));
  EXPECT_EQ(settings.transport, MeshlessTransport::hierarchical);
  SiteSamplingSettings sampling;
  sampling.grid = 16;
  sampling.spacing = 0.2;
  const SiteSet sites = sample_sites(*scene, sampling);
  const SiteHierarchy hierarchy(sites, 10);
  const MeshlessBasis basis(sites.sites, sites.radius, BasisKind::normalized);
  TransferSettings transfer;
  transfer.gather_rays = 4;
  transfer.max_entries = 2000;
  try {
    compute_transfer_matrix(*scene, sites, basis, sites.effective_area, transfer, nullptr, nullptr,
                            &hierarchy);
    FAIL() << "not refused";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("meshless.spacing"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("meshless.cluster_angle"), std::string::npos) << e.what();
  }
  for (const std::string bad :
       {R"({"transport": "wavelet"})", R"({"cluster_angle": -1})", R"({"cluster_angle": 11})"}) {
    try {  // refused where the scene is read, located at the key
      cube(0.5, bad);
      ADD_FAILURE() << "not refused: " << bad;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("cube.json:3:"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("meshless."), std::string::npos) << e.what();
    }
  }
}

// Objects farther apart than the spacing thin nothing until it passes their distance: the spacing
// doubles on without making levels, and the top level still ends small (it ended at 40 sites).
TEST(SiteHierarchy, ScatteredObjectsStillEndInASmallTopLevel) {
  SiteSet set;
  for (int group = 0; group < 40; ++group)
    for (int k = 0; k < 10; ++k) set.sites.push_back({Vec3{100.0 * group, 0.1 * k, 0}, Vec3{0, 0, 1}});
  set.spacing = 0.1;
  assign_radii(set, 4);
  const SiteHierarchy hierarchy(set, 4);
  EXPECT_LE(hierarchy.level_sites(hierarchy.level_count() - 1).size(), 16u);
  for (std::size_t l = 1; l < hierarchy.level_count(); ++l) {
    EXPECT_LT(hierarchy.level_sites(l).size(), hierarchy.level_sites(l - 1).size());
    EXPECT_GE(hierarchy.level_spacing(l), 2 * hierarchy.level_spacing(l - 1));
  }
}

// Uneven light — a point light in one corner of a closed grey box, a red wall — the hierarchical
// transport's λ against the flat matrix's, site by site; and the same bytes with one thread or two.
TEST(HierarchicalTransport, FollowsTheFlatSolutionUnderUnevenLightAndIgnoresThreads) {
  const std::string shapes = testing::closed_cube_shapes(R"({"kd": [0.7, 0.5, 0.4]})");
  const auto scene_with = [&](const std::string& transport) {
    return load_scene_text(R"({"format": "candela/1",
      "camera": {"eye": [1, 1.1, 1.7], "target": [0.9, 0.8, 0], "fov": 80, "width": 16, "height": 16},
      "render": {"method": "meshless"},
      "lights": [{"type": "point", "position": [0.3, 1.7, 0.3], "intensity": 1}],
      "meshless": {"transport": ")" +
                               transport + R"(", "spacing": 0.12, "grid": 32, "rounds": 6}, )" + shapes + "}",
                           "uneven.json", ".");
  };
  const MeshlessSolution flat = solve(*scene_with("flat"));
  const auto hierarchical_scene = scene_with("hierarchical");
  const MeshlessSolution hierarchical = solve(*hierarchical_scene);
  ASSERT_EQ(flat.sites.sites.size(), hierarchical.sites.sites.size());
  ASSERT_GT(hierarchical.matrix.receiver_links.nonZeros(), 0);
  double squares = 0, reference = 0, indirect_squares = 0;
  for (std::size_t i = 0; i < flat.transfer.lambda.size(); ++i) {
    const double a = flat.transfer.lambda[i].g, b = hierarchical.transfer.lambda[i].g;
    squares += (a - b) * (a - b);
    reference += a * a;
    const double indirect = a - flat.eta[i].g;
    indirect_squares += indirect * indirect;
  }
  // The difference is a small part of the indirect light (the only part the transport makes).
  EXPECT_LT(std::sqrt(squares / indirect_squares), 0.015) << "of the indirect light";  // 0.0037 measured
  EXPECT_LT(std::sqrt(squares / reference), 0.006) << "of the light";                  // 0.0018
  MeshlessSolution one_thread;
  {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    one_thread = solve(*hierarchical_scene);
  }
  ASSERT_EQ(one_thread.matrix.entries(), hierarchical.matrix.entries());
  for (std::size_t i = 0; i < one_thread.transfer.lambda.size(); ++i)
    ASSERT_EQ(one_thread.transfer.lambda[i].g, hierarchical.transfer.lambda[i].g) << "site " << i;
}

}  // namespace
}  // namespace candela
