// `mpirun -np 2 candela render` against one process, byte for byte: the built-in
// scene, every distributed method, checkpoints across rank counts, and bad input under mpirun.
// Built only with MPI (tests/CMakeLists.txt); every launch is bounded by `timeout`, so a hang fails.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "scratch_directory.h"

namespace candela {
namespace {

namespace fs = std::filesystem;

class Distributed : public ::testing::Test {
 protected:
  // candela with arguments, in one process (ranks 0) or under mpirun; returns the exit code and
  // fills output (stdout + stderr).
  int run(int ranks, const std::string& arguments, std::string& output) {
    const fs::path log = directory_.path() / "log.txt";
    std::string launcher = "timeout 300 ";
    if (ranks > 0)
      // Open MPI's plugins leak at exit (LeakSanitizer cannot even name them, they are unloaded by
      // then): leak checks stay with the single-process tests; every other check stays on.
      launcher +=
          "env OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 "
          "ASAN_OPTIONS=${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0 '" CANDELA_MPIEXEC "' -np " +
          std::to_string(ranks) + " --oversubscribe --bind-to none ";
    const std::string command = "cd '" + directory_.path().string() + "' && " + launcher +
                                "'" CANDELA_CLI "' " + arguments + " > '" + log.string() + "' 2>&1";
    const int status = std::system(command.c_str());
    output = bytes("log.txt");
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
  std::string bytes(const std::string& name) {
    std::ifstream in(directory_.path() / name, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
  }
  bool exists(const std::string& name) { return fs::exists(directory_.path() / name); }
  nlohmann::json json(const std::string& name) { return nlohmann::json::parse(bytes(name)); }
  // Renders arguments alone (-o NAME-1.EXT) and on two ranks (-o NAME-2.EXT); expects both to
  // succeed and the images to be identical.
  void expect_identical(const std::string& name, const std::string& arguments,
                        const std::string& extension = "pfm") {
    std::string output;
    ASSERT_EQ(run(0, arguments + " -o " + name + "-1." + extension, output), 0) << output;
    ASSERT_EQ(run(2, arguments + " -o " + name + "-2." + extension + " --stats " + name + "-2.json", output),
              0)
        << output;
    const std::string one = bytes(name + "-1." + extension), two = bytes(name + "-2." + extension);
    ASSERT_FALSE(one.empty());
    EXPECT_TRUE(one == two) << name << ": the two-rank image differs from the single-process one";
    const nlohmann::json stats = json(name + "-2.json");
    EXPECT_EQ(stats["ranks"], 2);
    ASSERT_TRUE(stats.contains("distributed")) << stats.dump();
    const nlohmann::json& facts = stats["distributed"];
    EXPECT_EQ(facts["ranks"], 2);
    ASSERT_EQ(facts["tiles_by_rank"].size(), 2u);
  }
  testing::ScratchDirectory directory_{"candela-distributed"};
};

const std::string kCornell =
    "'" CANDELA_SOURCE_DIR "/scenes/cornell-box.json' -q --set camera.width=96 --set camera.height=96";
// The Cornell box's radiosity on a coarser mesh (850 elements, 262 patches, 1098 shots instead of
// 3310, 890, 3941): the same rows, shots and checkpoints cross ranks, in a tenth of the time (the
// sanitizer run of CI took two minutes for the rows test alone).
const std::string kCornellRadiosity =
    "render " + kCornell +
    " --method radiosity --set radiosity.hemicube_resolution=40 --set radiosity.patch_size=4 "
    "--set radiosity.element_size=2";

// The built-in scene on two ranks (Whitted, 500 × 500, adaptive anti-aliasing with the
// Gaussian of 000 Figure 49), PNG byte for byte.
TEST_F(Distributed, BuiltInSceneOnTwoRanksIsByteIdentical) {
  expect_identical("default", "render -q", "png");
  const nlohmann::json stats = json("default-2.json");
  const auto& by_rank = stats["distributed"]["tiles_by_rank"];
  EXPECT_EQ(by_rank[0].get<int>() + by_rank[1].get<int>(), 64);  // 8 × 8 tiles of 64 pixels
  EXPECT_GT(stats["distributed"]["rank0_bytes_received"].get<double>(), 0);
  // Every rank's rays counted once: the per-pixel counts are the single process's; the total also
  // holds each tile's ring of pixels that the filter reaches, sampled again by its tile.
  std::string output;
  ASSERT_EQ(run(0, "render -q -o single.png --stats single.json", output), 0) << output;
  const nlohmann::json single = json("single.json");
  EXPECT_EQ(stats["rays"]["primary_per_pixel"], single["rays"]["primary_per_pixel"]);
  EXPECT_GT(stats["rays"]["primary"].get<int>(), single["rays"]["primary"].get<int>());
  EXPECT_LT(stats["rays"]["primary"].get<double>(), 1.1 * single["rays"]["primary"].get<double>());
  ASSERT_EQ(run(2, "render -q --set aa.mode=none --set aa.filter=box -o none.png --stats none.json", output),
            0)
      << output;
  EXPECT_EQ(json("none.json")["rays"]["primary"], 500 * 500);  // no ring: exactly one ray a pixel
}

TEST_F(Distributed, LocalAndAdaptiveWhittedWithTheirSampleMaps) {
  expect_identical("local", "render -q --method local --set camera.width=150 --set camera.height=100");
  std::string output;
  const std::string adaptive =
      "render -q --set camera.width=130 --set camera.height=70 --set aa.mode=adaptive";
  ASSERT_EQ(run(0, adaptive + " -o a1.pfm --aa-map map1.png", output), 0) << output;
  ASSERT_EQ(run(2, adaptive + " -o a2.pfm --aa-map map2.png", output), 0) << output;
  EXPECT_EQ(bytes("a1.pfm"), bytes("a2.pfm"));
  EXPECT_EQ(bytes("map1.png"), bytes("map2.png"));
}

// The rasterizer draws the tiles handed to its rank (each rank makes the view's triangles): the
// built-in scene's adaptive jittered passes, a grid of samples through a Gaussian filter, and
// Gouraud's vertex intensities. Before, every rank drew the whole image and no tile was shared.
TEST_F(Distributed, RasterTilesAcrossRanksAreByteIdentical) {
  expect_identical("raster-passes",
                   "render -q --method raster --set camera.width=150 --set camera.height=110");
  const nlohmann::json stats = json("raster-passes-2.json");
  const auto& by_rank = stats["distributed"]["tiles_by_rank"];
  EXPECT_EQ(by_rank[0].get<int>() + by_rank[1].get<int>(), 6);  // 3 × 2 tiles of 64 pixels
  EXPECT_GT(stats["raster"]["accumulation"]["refined_pixels"].get<int>(), 0);
  expect_identical("raster-grid",
                   "render " + kCornell +
                       " --method raster --set aa.mode=uniform --set aa.n=2 --set aa.filter=gaussian "
                       "--set raster.shading=gouraud");
}

TEST_F(Distributed, PathTracedImageIsByteIdentical) {
  expect_identical("path", "render " + kCornell + " --method path --spp 6");
  EXPECT_GE(json("path-2.json")["distributed"]["rounds"].get<int>(), 1);
}

// Each sampler's values depend on the pixel and the pass only, not on the rank.
TEST_F(Distributed, PathTracedImagesOfEverySamplerAreByteIdentical) {
  for (const char* sampler : {"stratified", "sobol"})
    expect_identical(std::string("path-") + sampler,
                     "render " + kCornell + " --method path --spp 4 --set path.sampler=" + sampler);
}

// The path tracer's samples splatted with a wide filter across the tiles' borders (each
// tile samples the ring of pixels its filter reaches) join into the single process's image.
TEST_F(Distributed, PathTracedImageWithAGaussianFilterIsByteIdentical) {
  expect_identical(
      "path-gaussian",
      "render " + kCornell + " --method path --spp 3 --set aa.filter=gaussian --set aa.filter_radius=2");
}

// The path tracer's lattice passes (aa.mode adaptive, jittered lattice, Gaussian): each tile takes
// the lattice points of its ring too, seeded by the point and the pass, and the tiles join into
// the single process's image.
TEST_F(Distributed, PathTracedAdaptiveLatticePassesAreByteIdentical) {
  expect_identical("path-adaptive", "render " + kCornell +
                                        " --method path --spp 2 --set aa.mode=adaptive --set aa.jitter=true "
                                        "--set aa.filter=gaussian");
}

// A checkpoint made by one process continues on two ranks, and one made on two ranks continues
// alone: both give the uninterrupted image.
TEST_F(Distributed, PathCheckpointsResumeAcrossRankCounts) {
  std::string output;
  const std::string path = "render " + kCornell + " --method path";
  ASSERT_EQ(run(0, path + " --spp 8 -o whole.pfm", output), 0) << output;
  ASSERT_EQ(run(0, path + " --spp 3 --checkpoint alone.ckpt -o part.pfm", output), 0) << output;
  ASSERT_EQ(run(2, path + " --spp 8 --resume alone.ckpt -o resumed-on-two.pfm", output), 0) << output;
  EXPECT_EQ(bytes("resumed-on-two.pfm"), bytes("whole.pfm"));
  ASSERT_EQ(run(2, path + " --spp 5 --checkpoint two.ckpt -o part2.pfm", output), 0) << output;
  ASSERT_EQ(run(0, path + " --spp 8 --resume two.ckpt -o resumed-alone.pfm", output), 0) << output;
  EXPECT_EQ(bytes("resumed-alone.pfm"), bytes("whole.pfm"));
}

TEST_F(Distributed, RadiosityRowsAcrossRanksGiveTheSameSolution) {
  // Progressive with hemicube rows, and the exported solution (B per element) alike.
  std::string output;
  const std::string& radiosity = kCornellRadiosity;
  ASSERT_EQ(run(0, radiosity + " -o h1.pfm --export-solution h1.csv", output), 0) << output;
  ASSERT_EQ(run(2, radiosity + " -o h2.pfm --export-solution h2.csv", output), 0) << output;
  EXPECT_EQ(bytes("h1.pfm"), bytes("h2.pfm"));
  ASSERT_FALSE(bytes("h1.csv").empty());
  EXPECT_EQ(bytes("h1.csv"), bytes("h2.csv"));
  // Ray-cast rows (random streams per row), Gauss-Seidel over patch rows, adaptive subdivision
  // (new element rows across ranks), and the Gouraud display.
  expect_identical("raycast",
                   radiosity + " --set radiosity.form_factors=ray-cast --set radiosity.ray_cast_samples=3");
  expect_identical(
      "seidel", radiosity + " --set radiosity.solver=gauss-seidel --set radiosity.subdivision_threshold=0.1");
  expect_identical("gouraud", radiosity + " --set radiosity.display=gouraud");
}

TEST_F(Distributed, RadiosityCheckpointResumesOnTwoRanks) {
  std::string output;
  const std::string& radiosity = kCornellRadiosity;
  ASSERT_EQ(run(0, radiosity + " -o whole.pfm", output), 0) << output;
  ASSERT_EQ(run(0, radiosity + " --set radiosity.max_steps=15 --checkpoint shots.ckpt -o part.pfm", output),
            0)
      << output;
  ASSERT_EQ(run(2, radiosity + " --resume shots.ckpt -o resumed.pfm", output), 0) << output;
  EXPECT_EQ(bytes("resumed.pfm"), bytes("whole.pfm"));
}

TEST_F(Distributed, MeshlessTransferRowsAcrossRanksGiveTheSameImage) {
  expect_identical(
      "meshless",
      "render " + kCornell + " --method meshless --set meshless.spacing=0.5 --set meshless.gather_rays=16");
  const nlohmann::json two = json("meshless-2.json");
  std::string output;
  ASSERT_EQ(run(0,
                "render " + kCornell +
                    " --method meshless --set meshless.spacing=0.5 --set meshless.gather_rays=16 -o m.pfm "
                    "--stats m.json",
                output),
            0);
  EXPECT_EQ(json("m.json")["meshless"]["transfer_entries"], two["meshless"]["transfer_entries"]);
  EXPECT_EQ(json("m.json")["meshless"]["visibility_rays"], two["meshless"]["visibility_rays"]);
}

// The hierarchical transport across ranks — the sites' rows shared out, the links of the
// hierarchy computed alike on every rank — gives the single process's image and matrix.
TEST_F(Distributed, HierarchicalMeshlessTransportAcrossRanksGivesTheSameImage) {
  const std::string arguments = "render " + kCornell +
                                " --method meshless --set meshless.spacing=0.4 --set meshless.gather_rays=16 "
                                "--set meshless.transport=hierarchical";
  expect_identical("hierarchical", arguments);
  std::string output;
  ASSERT_EQ(run(0, arguments + " -o h.pfm --stats h.json", output), 0) << output;
  const nlohmann::json two = json("hierarchical-2.json");
  EXPECT_GT(json("h.json")["meshless"]["cluster_links"].get<int>(), 0);
  EXPECT_EQ(json("h.json")["meshless"]["transfer_entries"], two["meshless"]["transfer_entries"]);
  EXPECT_EQ(json("h.json")["meshless"]["cluster_links"], two["meshless"]["cluster_links"]);
}

// 002 §5.3 relighting reuses the sites and S: each frame, and the sites picture (written by rank
// 0 alone), as one process makes them.
TEST_F(Distributed, MeshlessRelightFramesAndSitesPicture) {
  const std::string light = R"({"type": "point", "position": [5, 7, 5], "intensity": 10})";
  std::ofstream(directory_.path() / "room.json") << R"({"format": "candela/1",
    "camera": {"eye": [5, 4, 9.5], "target": [5, 4, 0], "fov": 60, "width": 40, "height": 30},
    "meshless": {"spacing": 1.5, "grid": 12, "rounds": 1},
    "lights": [)" + light + R"(],
    "shapes": [{"type": "box", "min": [0, 0, 0], "max": [10, 8, 10], "material": {"kd": 0.6}}]})";
  std::ofstream(directory_.path() / "lights.json") << R"({"frames": [
    {"name": "low", "lights": [{"type": "point", "position": [2, 1, 5], "intensity": 10}]},
    {"name": "area", "ambient": 0.1, "lights": [{"type": "area", "corner": [4, 7.9, 4], "edge_u": [2, 0, 0], "edge_v": [0, 0, 2], "exitance": 20}]}]})";
  std::string output;
  const std::string relight = "render room.json -q --method meshless --relight lights.json";
  ASSERT_EQ(run(0, relight + " -o one.pfm --show-sites one-sites.png", output), 0) << output;
  ASSERT_EQ(run(2, relight + " -o two.pfm --show-sites two-sites.png", output), 0) << output;
  for (const char* name : {".pfm", "-low.pfm", "-area.pfm", "-sites.png"}) {
    ASSERT_FALSE(bytes(std::string("one") + name).empty()) << name;
    EXPECT_EQ(bytes(std::string("one") + name), bytes(std::string("two") + name)) << name;
  }
}

TEST_F(Distributed, SeveralCamerasEachByteIdentical) {
  std::string output;
  ASSERT_EQ(run(0, "render " + kCornell + " --camera all -o one.pfm", output), 0) << output;
  ASSERT_EQ(run(2, "render " + kCornell + " --camera all -o two.pfm", output), 0) << output;
  for (const char* view : {"front", "corner", "floor"})
    EXPECT_EQ(bytes(std::string("one-") + view + ".pfm"), bytes(std::string("two-") + view + ".pfm")) << view;
}

// Bad input under mpirun: one message (from rank 0), a non-zero exit, no output, no hang.
TEST_F(Distributed, BadInputIsReportedOnceAndWritesNothing) {
  std::ofstream(directory_.path() / "bad.json") << "{\"format\": \"candela/1\", \"camera\": {\"width\": -3}}";
  std::string output;
  EXPECT_NE(run(2, "render bad.json -o out.png", output), 0);
  EXPECT_FALSE(exists("out.png"));
  const std::size_t first = output.find("candela: error:");
  ASSERT_NE(first, std::string::npos) << output;
  EXPECT_EQ(output.find("candela: error:", first + 1), std::string::npos) << "reported more than once:\n"
                                                                          << output;
  EXPECT_NE(output.find("bad.json"), std::string::npos) << output;

  // A checkpoint of another scene: rank 0 reads it and refuses; the other rank stops with it.
  ASSERT_EQ(run(0, "render " + kCornell + " --method path --spp 2 --checkpoint box.ckpt -o box.pfm", output),
            0)
      << output;
  EXPECT_NE(run(2,
                "render -q --method path --set aa.mode=none --set aa.filter=box --spp 4 --resume box.ckpt -o "
                "other.pfm",
                output),
            0);
  EXPECT_NE(output.find("another scene"), std::string::npos) << output;
  EXPECT_FALSE(exists("other.pfm"));

  // Only render is distributed.
  EXPECT_NE(run(2, "info", output), 0);
  EXPECT_NE(output.find("without mpirun"), std::string::npos) << output;
}

}  // namespace
}  // namespace candela
