// Tests of the site sampling of seed 002 §4.2.6 (meshless/site_sampling.h).
#include "meshless/site_sampling.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <string>

#include "math/constants.h"
#include "scene/scene_loader.h"

namespace candela {
namespace {

// The camera inside a closed sphere of radius 2: the secondary rounds reach what the camera cannot.
std::unique_ptr<Scene> inside_sphere() {
  return read_scene_text(R"({"format": "candela/1",
    "camera": {"eye": [0, 0, 0], "target": [0, 0, -1], "fov": 60, "width": 32, "height": 32},
    "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 2}]})",
                         "test.json", ".", {}, {});
}

TEST(SiteSampling, CoversAClosedSphereAndKeepsTheSpacing) {
  const auto scene = inside_sphere();
  SiteSamplingSettings settings;
  settings.grid = 32;
  settings.rounds = 6;
  settings.spacing = 0.25;
  const SiteSet set = sample_sites(*scene, settings);
  ASSERT_GT(set.sites.size(), set.camera_sites);  // the rounds added sites
  EXPECT_GT(set.camera_sites, 0u);
  double area = 0;
  bool reached_back = false;
  for (std::size_t i = 0; i < set.sites.size(); ++i) {
    const Site& site = set.sites[i];
    EXPECT_NEAR(length(site.position), 2, 1e-9);
    EXPECT_NEAR(dot(site.normal, site.position / 2), -1, 1e-9);  // seen from inside: inward normals
    reached_back |= site.position.z > 1.5;                       // behind the camera
    for (std::size_t j = 0; j < i; ++j) EXPECT_GE(site_distance(site, set.sites[j]), settings.spacing);
    area += set.effective_area[i];
  }
  EXPECT_TRUE(reached_back);
  // The effective areas of a well-covered closed surface add up to its area (002 eq. 5.4).
  RecordProperty("area_ratio", std::to_string(area / (16 * kPi)));
  EXPECT_NEAR(area, 16 * kPi, 0.1 * 16 * kPi);
}

TEST(SiteSampling, DoesNotDependOnTheThreadCount) {
  const auto scene = inside_sphere();
  SiteSamplingSettings settings;
  settings.grid = 16;
  settings.rounds = 3;
  settings.spacing = 0.3;
  SiteSet one, two;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    one = sample_sites(*scene, settings);
  }
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
    two = sample_sites(*scene, settings);
  }
  ASSERT_EQ(one.sites.size(), two.sites.size());
  for (std::size_t i = 0; i < one.sites.size(); ++i) {
    EXPECT_EQ(one.sites[i].position, two.sites[i].position);
    EXPECT_EQ(one.radius[i], two.radius[i]);
  }
}

TEST(SiteSampling, BadSettingsAreRefused) {
  const auto scene = inside_sphere();
  SiteSamplingSettings settings;
  settings.grid = 0;
  EXPECT_THROW(sample_sites(*scene, settings), std::invalid_argument);
  settings = {};
  settings.spacing = -1;
  EXPECT_THROW(sample_sites(*scene, settings), std::invalid_argument);
  settings = {};
  settings.neighbours = 0;
  EXPECT_THROW(sample_sites(*scene, settings), std::invalid_argument);
  settings = {};
  settings.spacing = 1e-6;
  settings.max_sites = 100;
  EXPECT_THROW(sample_sites(*scene, settings), std::invalid_argument);
}

}  // namespace
}  // namespace candela
