// SPEC §15: "Ctrl-C writes what is done; never lose a finished result." Every
// method stops early once cancellation is requested and says so in its statistics; `candela
// render` writes the partial image, exits with 130, and the path tracer's checkpoint continues to
// the same image as a run that was never interrupted.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <spawn.h>
#include <sys/wait.h>
#include <tbb/global_control.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "camera/antialiasing.h"
#include "integrators/method_registry.h"
#include "integrators/pass_checkpoint.h"
#include "integrators/scene_loading.h"
#include "io/image_reader.h"
#include "render_support.h"
#include "scratch_directory.h"
#include "util/cancellation.h"

extern char** environ;

namespace candela {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// Resets the flag on the way out, whatever the test did.
struct CancellationGuard {
  CancellationGuard() { reset_cancellation(); }
  ~CancellationGuard() { reset_cancellation(); }
};

// An emitting, reflecting sphere around the camera: every method sees something in every pixel.
std::unique_ptr<Scene> furnace(const std::string& method, const std::string& extra = "",
                               const std::string& radiosity = R"({"patch_size": 1, "element_size": 1})") {
  return load_scene_text(R"({"format": "candela/1",
    "camera": {"eye": [0, 0, 0], "target": [0, 0, -1], "fov": 60, "width": 24, "height": 24},
    "render": {"method": ")" +
                             method + R"("}, )" + extra + R"(
    "radiosity": )" + radiosity +
                             R"(,
    "meshless": {"spacing": 0.5, "grid": 12, "rounds": 2},
    "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 2, "material": {"kd": 0.5, "emission": 1}}]})",
                         "furnace.json", ".");
}

bool all_black(const Film& film) {
  for (const Color& c : film.pixels())
    if (!c.is_black()) return false;
  return true;
}

// Cancelled before it starts, every method returns at once with nothing (or, radiosity, the
// emission alone) and says it was interrupted.
TEST(Interrupt, EveryMethodStopsWhenCancelledBeforeItStarts) {
  const CancellationGuard guard;
  for (const std::string method : {"local", "whitted", "raster", "radiosity", "meshless", "path"}) {
    const auto scene = furnace(method);
    const auto renderer = create_method(*find_method(method), *scene);
    Film film(scene->camera->width(), scene->camera->height());
    RunStatistics statistics;
    request_cancellation();
    const auto start = Clock::now();
    testing::render_into(*renderer, *scene, {{0, 0, film.width(), film.height()}, true}, film, statistics);
    EXPECT_LT(std::chrono::duration<double>(Clock::now() - start).count(), 10.0) << method;
    EXPECT_TRUE(statistics.extra.value("interrupted", false)) << method;
    EXPECT_TRUE(statistics.extra.contains("completed")) << method;
    if (method != "radiosity") {  // radiosity shows B = E
      EXPECT_TRUE(all_black(film)) << method;
    }
    reset_cancellation();
    // Not cancelled: the same method renders the whole image and says nothing of interruption.
    Film whole(film.width(), film.height());
    RunStatistics normal;
    testing::render_into(*renderer, *scene, {{0, 0, whole.width(), whole.height()}, true}, whole, normal);
    EXPECT_FALSE(normal.extra.contains("interrupted")) << method;
    EXPECT_FALSE(all_black(whole)) << method;
  }
}

// Hierarchical radiosity, cancelled before it starts, neither refines nor iterates and
// says it was interrupted; then, not cancelled, it solves (the sphere faces out, away from the
// camera inside it: B = E, nothing is seen back).
TEST(Interrupt, HierarchicalRadiosityStopsWhenCancelledBeforeItStarts) {
  const CancellationGuard guard;
  const auto scene = furnace("radiosity", "", R"({"solver": "hierarchical"})");
  const auto renderer = create_method(*find_method("radiosity"), *scene);
  Film film(scene->camera->width(), scene->camera->height());
  RunStatistics statistics;
  request_cancellation();
  testing::render_into(*renderer, *scene, {{0, 0, film.width(), film.height()}, true}, film, statistics);
  EXPECT_TRUE(statistics.extra.value("interrupted", false));
  const auto& facts = statistics.extra["radiosity"];
  EXPECT_EQ(facts["steps"], 0);
  EXPECT_EQ(facts["links"], 1);  // the root cluster's own link, never split
  EXPECT_FALSE(facts["converged"].get<bool>());
  reset_cancellation();
  Film whole(film.width(), film.height());
  RunStatistics normal;
  testing::render_into(*renderer, *scene, {{0, 0, whole.width(), whole.height()}, true}, whole, normal);
  EXPECT_FALSE(normal.extra.contains("interrupted"));
  EXPECT_TRUE(normal.extra["radiosity"]["converged"].get<bool>());
  EXPECT_GT(normal.extra["radiosity"]["steps"].get<int>(), 0);
  EXPECT_NEAR(whole.at(12, 12).g, 1, 1e-3);
}

// Cancelled in the middle of the tiles: the finished tiles keep their pixels, the others are black.
TEST(Interrupt, SampleImageKeepsTheFinishedTiles) {
  const CancellationGuard guard;
  const tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
  Film film(16, 16);
  std::atomic<int> calls{0};
  const RadianceFunction radiance = [&](double, double) {
    if (++calls == 4 * 4 * 2) request_cancellation();  // in the second tile of 4 × 4
    return Color(1);
  };
  int tiles_done = 0;
  sample_image(AntialiasingSettings{}, 1, {0, 0, 16, 16}, 4, radiance, film, [&] { ++tiles_done; });
  EXPECT_EQ(tiles_done, 2);  // the tile in progress is finished, no other is begun
  int lit = 0;
  for (const Color& c : film.pixels()) lit += c.r == 1;
  EXPECT_EQ(lit, 2 * 16);
}

// Cancelled while passes run (here: asked after exactly the third pass, through the request's
// on_progress hook, so the test is the same on every machine and under sanitizers): the run stops
// before the next pass, says it was interrupted, and the image is the mean of the whole passes,
// bit for bit the image of a run asked for that many.
TEST(Interrupt, PathTracerKeepsTheMeanOfWholePasses) {
  const CancellationGuard guard;
  const auto scene = furnace("path", R"("path": {"spp": 1000000},)");
  const auto renderer = create_method(*find_method("path"), *scene);
  RenderRequest request{{0, 0, 24, 24}, true};
  request.on_progress = [](const ProgressStep& step) {
    if (step.work == 3) request_cancellation();
  };
  const RenderResult interrupted = renderer->render(*scene, request);
  reset_cancellation();
  EXPECT_TRUE(interrupted.statistics.extra.value("interrupted", false));
  EXPECT_EQ(interrupted.statistics.extra["path"]["spp"].get<uint64_t>(), 3u);
  const auto exact = furnace("path", R"("path": {"spp": 3},)");
  const RenderResult reference =
      create_method(*find_method("path"), *exact)->render(*exact, {{0, 0, 24, 24}, true});
  EXPECT_FALSE(reference.statistics.extra.value("interrupted", false));
  EXPECT_EQ(interrupted.film.pixels(), reference.film.pixels());
}

// The candela executable, started in the background.
class Process {
 public:
  Process(const fs::path& directory, const std::vector<std::string>& arguments) {
    std::vector<std::string> words{CANDELA_CLI};
    words.insert(words.end(), arguments.begin(), arguments.end());
    std::vector<char*> argv;
    for (std::string& word : words) argv.push_back(word.data());
    argv.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    const std::string log = (directory / "log.txt").string();
    posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&actions, 1, 2);
    started_ = posix_spawn(&pid_, words[0].c_str(), &actions, nullptr, argv.data(), environ) == 0;
    posix_spawn_file_actions_destroy(&actions);
  }
  ~Process() {
    if (started_ && !waited_) {
      kill(pid_, SIGKILL);
      waitpid(pid_, nullptr, 0);
    }
  }
  bool started() const { return started_; }
  // False once it has ended (its status is then kept for wait).
  bool running() {
    if (waited_) return false;
    const pid_t ended = waitpid(pid_, &status_, WNOHANG);
    if (ended == pid_) waited_ = true;
    return !waited_;
  }
  void signal(int number) const { kill(pid_, number); }
  // The exit status, or -1 when it ended otherwise (a signal).
  int wait() {
    if (!waited_) waitpid(pid_, &status_, 0);
    waited_ = true;
    return WIFEXITED(status_) ? WEXITSTATUS(status_) : -1;
  }

 private:
  pid_t pid_ = 0;
  int status_ = 0;
  bool started_ = false, waited_ = false;
};

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

int run_candela(const fs::path& directory, const std::vector<std::string>& arguments) {
  Process process(directory, arguments);
  return process.started() ? process.wait() : -1;
}

// Ctrl-C during a long path-traced run: exit status 130, the mean of the passes done written as
// the image, the checkpoint holds the same passes and --resume goes on from it to the bytes of a
// run that was never interrupted.
TEST(Interrupt, CtrlCWritesThePartialImageAndACheckpointThatResumes) {
  const testing::ScratchDirectory scratch("candela-interrupt");
  const fs::path& dir = scratch.path();
  const std::string scene = CANDELA_SOURCE_DIR "/scenes/cornell-box.json";
  const std::vector<std::string> common{
      "render",           scene,       "-q", "--method", "path", "--set", "camera.width=12", "--set",
      "camera.height=10", "--threads", "2"};
  const auto with = [&](std::vector<std::string> extra) {
    std::vector<std::string> all = common;
    all.insert(all.end(), extra.begin(), extra.end());
    return all;
  };
  const fs::path checkpoint = dir / "run.ckpt", output = dir / "partial.pfm", stats = dir / "stats.json";
  {
    Process process(dir, with({"--spp", "16000000", "--checkpoint", checkpoint.string(), "--checkpoint-every",
                               "0.05", "-o", output.string(), "--stats", stats.string()}));
    ASSERT_TRUE(process.started());
    // The first checkpoint says the passes have begun.
    const auto deadline = Clock::now() + std::chrono::seconds(60);
    while (!fs::exists(checkpoint) && process.running() && Clock::now() < deadline)
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    ASSERT_TRUE(fs::exists(checkpoint)) << read_text(dir / "log.txt");
    ASSERT_TRUE(process.running()) << read_text(dir / "log.txt");
    process.signal(SIGINT);
    EXPECT_EQ(process.wait(), kInterruptedExitCode) << read_text(dir / "log.txt");
  }
  const std::string log = read_text(dir / "log.txt");
  EXPECT_NE(log.find("interrupted: partial result"), std::string::npos) << log;
  EXPECT_NE(log.find("--resume " + checkpoint.string()), std::string::npos) << log;
  const auto statistics = nlohmann::json::parse(read_text(stats));
  EXPECT_TRUE(statistics["interrupted"].get<bool>());
  const auto passes = statistics["path"]["spp"].get<uint64_t>();
  ASSERT_GT(passes, 0u);
  EXPECT_EQ(unseal_pass_checkpoint("path", read_checkpoint_file(checkpoint.string())).passes, passes);
  const Film partial = read_pfm(output.string());
  EXPECT_EQ(partial.width(), 12);
  EXPECT_FALSE(all_black(partial));

  // Two passes more from the checkpoint, and the same number in one uninterrupted run.
  const std::string total = std::to_string(passes + 2);
  const std::string resumed = (dir / "resumed.pfm").string(), whole = (dir / "whole.pfm").string();
  ASSERT_EQ(run_candela(dir, with({"--spp", total, "--resume", checkpoint.string(), "-o", resumed})), 0)
      << read_text(dir / "log.txt");
  ASSERT_EQ(run_candela(dir, with({"--spp", total, "-o", whole})), 0) << read_text(dir / "log.txt");
  EXPECT_EQ(read_text(resumed), read_text(whole));
}

}  // namespace
}  // namespace candela
