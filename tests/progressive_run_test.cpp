// The shared run loop (integrators/pass_method.h, progressive_run.h) gives a method rendered in
// passes its checkpoints, resume, ranks, progress, Ctrl-C and error log: the toy method below
// supplies one pass and its settings, nothing else. Runs as one process and under
// `mpirun -np 3` (ctest distributed.one_process, distributed.three_ranks): every rank calls every
// render, rank 0 checks the image.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "distributed/cluster.h"
#include "integrators/pass_method.h"
#include "integrators/scene_loading.h"
#include "util/cancellation.h"
#include "util/error.h"

namespace candela {
namespace {

// ---- The toy method: a constant image refined per pass ----
// Pass k adds `value` + (−1)^k · x / 100 at pixel x (weight 1), so an even number of passes gives
// `value` exactly and an odd number n gives value + x / (100 n).
class ToyPasses final : public PixelPasses {
 public:
  ToyPasses(double value, const PixelRect& region) : value_(value), region_(region) {}
  bool run_pass(uint64_t pass, const PixelBox& pixels, Color* sums, double* weights, uint64_t&) override {
    if (cancel_requested()) return false;
    for (int j = pixels.y0; j < pixels.y1; ++j)
      for (int i = pixels.x0; i < pixels.x1; ++i) {
        const std::size_t q = std::size_t(j - pixels.y0) * pixels.width() + (i - pixels.x0);
        sums[q] += Color(value_ + (pass % 2 == 0 ? 1 : -1) * (region_.x0 + i) / 100.0);
        weights[q] += 1;
      }
    return true;
  }
  RayCounts rays() const override { return {}; }

 private:
  double value_;
  PixelRect region_;
};

class ToyMethod final : public PassMethod {
 public:
  ToyMethod(double value, int passes) : value_(value), passes_(passes) {}
  std::string_view name() const override { return "toy"; }

 protected:
  std::string pass_fingerprint() const override { return fmt::format("value={}", value_); }
  RunLimits limits() const override { return {uint64_t(passes_), "toy.passes", 0, 1e-9}; }
  std::unique_ptr<PixelPasses> start_passes(const Scene&, const RenderRequest& request) const override {
    return std::make_unique<ToyPasses>(value_, request.region);
  }

 private:
  double value_;
  int passes_;
};
// ---- end of the toy method ----

class ProgressiveRunTest : public testing::Test {
 protected:
  // 150 × 70 pixels: six tiles of the ranks' 64-pixel tiles, so every rank of three takes some.
  std::unique_ptr<Scene> scene = load_default_scene({"camera.width=150", "camera.height=70"});
  Cluster& cluster = world_cluster();

  RenderRequest request() const {
    RenderRequest r;
    r.region = {0, 0, 150, 70};
    r.quiet = true;
    r.cluster = &cluster;
    r.fingerprint = "toy scene";
    return r;
  }
  // The toy's pixel after n passes.
  static double expected(double value, int x, int passes) {
    return passes % 2 == 0 ? value : value + x / (100.0 * passes);
  }
  static void expect_image(const Film& film, double value, int passes) {
    for (int j = 0; j < film.height(); ++j)
      for (int i = 0; i < film.width(); ++i)
        ASSERT_NEAR(film.at(i, j).g, expected(value, i, passes), 1e-12) << i << "," << j;
  }
  static void expect_same_bits(const Film& a, const Film& b) {
    for (int j = 0; j < a.height(); ++j)
      for (int i = 0; i < a.width(); ++i) ASSERT_EQ(a.at(i, j), b.at(i, j)) << i << "," << j;
  }
};

TEST_F(ProgressiveRunTest, PassesRefineTheImageAndReportEachStep) {
  std::vector<uint64_t> steps;
  RenderRequest r = request();
  r.on_progress = [&](const ProgressStep& step) {
    EXPECT_EQ(step.unit, "passes");
    steps.push_back(step.work);
    // The error log's image is the state's: the mean of the passes so far (on one process; across
    // ranks the state of the round that holds the pass, RenderRequest::on_progress).
    if (!cluster.distributed()) {
      EXPECT_NEAR(step.image().at(30, 5).g, expected(2, 30, int(step.work)), 1e-12);
    }
  };
  const RenderResult result = ToyMethod(2, 5).render(*scene, r);
  if (!cluster.root()) return;
  expect_image(result.film, 2, 5);
  EXPECT_EQ(steps, (std::vector<uint64_t>{1, 2, 3, 4, 5}));
  EXPECT_EQ(result.statistics.extra["toy"]["spp"], 5);
  EXPECT_EQ(result.statistics.extra["toy"]["passes_this_run"], 5);
  EXPECT_EQ(result.statistics.extra.contains("distributed"), cluster.distributed());
}

TEST_F(ProgressiveRunTest, CheckpointsResumeToTheUninterruptedImage) {
  const RenderResult whole = ToyMethod(0.5, 7).render(*scene, request());
  // Checkpoints between passes (the toy's interval is 1e-9 s) and at the end.
  std::vector<Bytes> saved;
  RenderRequest first = request();
  first.checkpoint = true;
  first.save_checkpoint = [&](const Bytes& sealed) { saved.push_back(sealed); };
  const RenderResult part = ToyMethod(0.5, 3).render(*scene, first);
  RenderRequest again = request();
  again.resume = SealedCheckpoint{"part.checkpoint", cluster.root() ? *part.checkpoint : Bytes()};
  const RenderResult resumed = ToyMethod(0.5, 7).render(*scene, again);
  if (cluster.root()) {
    EXPECT_FALSE(saved.empty());
    EXPECT_EQ(part.statistics.extra["toy"]["checkpoints_written"].get<int>(), int(saved.size()) + 1);
    expect_same_bits(resumed.film, whole.film);
    EXPECT_EQ(resumed.statistics.extra["toy"]["resumed_from_spp"], 3);
    EXPECT_EQ(resumed.statistics.extra["toy"]["passes_this_run"], 4);
  }
  // Another value (a setting that shapes a pass) is refused; more passes than the limit too.
  const auto refused = [&](const ToyMethod& method, const std::string& why) {
    try {
      (void)method.render(*scene, again);
      ADD_FAILURE() << why << ": resumed";
    } catch (const InputError& e) {
      if (cluster.root()) {
        EXPECT_NE(std::string(e.what()).find(why), std::string::npos) << e.what();
      }
    } catch (const PeerFailure&) {
      EXPECT_FALSE(cluster.root());
    }
  };
  refused(ToyMethod(0.75, 7), "another scene or other settings");
  refused(ToyMethod(0.5, 2), "already holds 3 samples per pixel, more than toy.passes = 2");
}

TEST_F(ProgressiveRunTest, CtrlCKeepsTheWholePassesAndTheirCheckpoint) {
  RenderRequest r = request();
  r.checkpoint = true;
  r.on_progress = [](const ProgressStep& step) {
    if (step.work == 4) request_cancellation();  // rank 0 alone: the others learn it from the plan
  };
  const RenderResult result = ToyMethod(1, 1000).render(*scene, r);
  reset_cancellation();
  cluster.any(false);  // every rank past the render before the next test
  if (!cluster.root()) return;
  EXPECT_EQ(result.statistics.extra["interrupted"], true);
  EXPECT_EQ(result.statistics.extra["toy"]["spp"], 4);
  EXPECT_EQ(result.statistics.extra["completed"], "4 passes");
  expect_image(result.film, 1, 4);
  ASSERT_TRUE(result.checkpoint.has_value());
}

}  // namespace
}  // namespace candela
