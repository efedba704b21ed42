#include "bench/raster_bench.h"

#include <gtest/gtest.h>

#include <stdexcept>

namespace candela {
namespace {

TEST(RasterBench, ReportsEveryPassOfASmallMesh) {
  const BenchMesh sphere = bench_sphere(200);  // 168 triangles
  RasterBenchOptions options;
  options.width = 64;
  options.height = 48;
  options.repeat = 2;
  options.min_seconds = 0;
  const RasterBenchReport report = run_raster_bench(sphere, options);
  EXPECT_EQ(report.mesh, "sphere 200");
  EXPECT_EQ(report.triangles, 168u);
  ASSERT_EQ(report.passes.size(), 4u);
  const char* names[] = {"item_buffer", "depth", "gouraud", "phong"};
  for (std::size_t i = 0; i < 4; ++i) {
    const RasterPassResult& pass = report.passes[i];
    EXPECT_EQ(pass.pass, names[i]);
    EXPECT_EQ(pass.frames, 2);
    EXPECT_GT(pass.mtriangles_per_s, 0);
    // The framed sphere fills about half of the height: every pass sees the same fragments.
    EXPECT_GT(pass.fragments, 64u * 48u / 8);
    EXPECT_EQ(pass.fragments, report.passes[0].fragments);
    EXPECT_EQ(pass.written, report.passes[0].written);
    EXPECT_LE(pass.written, pass.fragments);
    EXPECT_EQ(pass.clipped, 0u);  // near and far lie outside the bounding sphere
  }
  const nlohmann::json json = report.to_json();
  EXPECT_EQ(json["triangles"], 168);
  EXPECT_EQ(json["width"], 64);
  EXPECT_EQ(json["passes"].size(), 4u);
  EXPECT_EQ(json["passes"][1]["pass"], "depth");
  EXPECT_NE(report.table().find("item_buffer"), std::string::npos);
}

TEST(RasterBench, RejectsBadOptions) {
  const BenchMesh sphere = bench_sphere(50);
  RasterBenchOptions options;
  options.width = 0;
  EXPECT_THROW(run_raster_bench(sphere, options), std::invalid_argument);
  options = {};
  options.fov_degrees = 180;
  EXPECT_THROW(run_raster_bench(sphere, options), std::invalid_argument);
  options = {};
  options.repeat = 0;
  EXPECT_THROW(run_raster_bench(sphere, options), std::invalid_argument);
}

}  // namespace
}  // namespace candela
