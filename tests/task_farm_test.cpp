// The task farm and the cluster's collectives. The same binary runs as one process
// (ctest distributed.one_process) and under `mpirun -np 3` (distributed.three_ranks): every rank
// runs every test in the same order, so the collectives inside them line up.
#include "distributed/task_farm.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <numeric>
#include <thread>

#include "distributed/cluster.h"
#include "integrators/scene_loading.h"
#include "meshless/meshless_basis.h"
#include "meshless/site_sampling.h"
#include "meshless/transfer_matrix.h"
#include "scene/scene.h"
#include "util/cancellation.h"

namespace candela {
namespace {

Bytes number_bytes(uint64_t value) {
  ByteWriter writer;
  writer.put(value);
  return writer.take();
}

uint64_t read_number(std::span<const std::byte> bytes) {
  return ByteReader(bytes).get<uint64_t>();
}

// A task's result is a function of the task alone: its square, and the input passed along.
TEST(TaskFarm, EveryTaskIsCollectedOnceWithItsOwnResult) {
  Cluster& cluster = world_cluster();
  for (const std::size_t count :
       {std::size_t(0), std::size_t(1), std::size_t(2), std::size_t(5), std::size_t(200)}) {
    std::vector<int> collected(count, 0);
    std::vector<uint64_t> results(count, 0);
    TaskFarm farm;
    farm.task_count = count;
    farm.input = [](std::size_t task) { return number_bytes(1000 + task); };
    farm.work = [](std::size_t task, std::span<const std::byte> input) {
      EXPECT_EQ(read_number(input), 1000 + task);
      return number_bytes(task * task + read_number(input));
    };
    farm.collect = [&](std::size_t task, Bytes result) {
      ASSERT_LT(task, count);
      ++collected[task];
      results[task] = read_number(result);
    };
    const TaskFarmReport report = run_task_farm(cluster, farm);
    if (!cluster.root()) continue;
    EXPECT_EQ(report.tasks_done, count);
    ASSERT_EQ(report.tasks_by_rank.size(), std::size_t(cluster.size()));
    EXPECT_EQ(std::accumulate(report.tasks_by_rank.begin(), report.tasks_by_rank.end(), uint64_t{0}), count);
    for (std::size_t task = 0; task < count; ++task) {
      EXPECT_EQ(collected[task], 1) << "task " << task << " of " << count;
      EXPECT_EQ(results[task], task * task + 1000 + task);
    }
  }
}

// Dynamic scheduling: a rank whose tasks take long does fewer of them.
TEST(TaskFarm, ASlowRankTakesFewerTasks) {
  Cluster& cluster = world_cluster();
  if (!cluster.distributed()) GTEST_SUCCEED() << "one process: nothing to balance";
  const std::size_t count = 60;
  TaskFarm farm;
  farm.task_count = count;
  farm.work = [&](std::size_t, std::span<const std::byte>) {
    // Rank 1 is ten times slower than the others.
    std::this_thread::sleep_for(std::chrono::milliseconds(cluster.rank() == 1 ? 20 : 2));
    return Bytes();
  };
  std::size_t collected = 0;
  farm.collect = [&](std::size_t, Bytes) { ++collected; };
  const TaskFarmReport report = run_task_farm(cluster, farm);
  if (!cluster.root() || !cluster.distributed()) return;
  EXPECT_EQ(collected, count);
  for (std::size_t rank = 0; rank < report.tasks_by_rank.size(); ++rank)
    if (rank != 1) {
      EXPECT_GT(report.tasks_by_rank[rank], report.tasks_by_rank[1]) << "rank " << rank;
    }
}

// stop() ends the handing out: the tasks given out are still collected, no more.
TEST(TaskFarm, StopEndsHandingOut) {
  Cluster& cluster = world_cluster();
  std::atomic<std::size_t> handed{0};
  std::size_t collected = 0;
  TaskFarm farm;
  farm.task_count = 1000;
  farm.work = [](std::size_t task, std::span<const std::byte>) { return number_bytes(task); };
  farm.collect = [&](std::size_t task, Bytes result) {
    EXPECT_EQ(read_number(result), task);
    ++collected;
  };
  farm.stop = [&] { return handed.fetch_add(1) >= 10; };
  const TaskFarmReport report = run_task_farm(cluster, farm);
  if (!cluster.root()) return;
  EXPECT_EQ(collected, report.tasks_done);
  EXPECT_LE(report.tasks_done, 10u);
  EXPECT_GE(report.tasks_done, 1u);
}

// An error in a task on rank 0 comes back from run_task_farm once the others are done.
TEST(TaskFarm, AWorkErrorOnRankZeroIsRethrown) {
  Cluster& cluster = world_cluster();
  TaskFarm farm;
  farm.task_count = 20;
  farm.work = [&](std::size_t task, std::span<const std::byte>) {
    if (cluster.root()) throw std::runtime_error("broken task " + std::to_string(task));
    // The other ranks are slow, so that rank 0 surely takes a task: on a loaded machine they once
    // took all 20 before rank 0's worker asked, and nothing was thrown (a flaky three_ranks).
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    return number_bytes(task);
  };
  farm.collect = [](std::size_t, Bytes) {};
  if (cluster.root()) {
    EXPECT_THROW(run_task_farm(cluster, farm), std::runtime_error);
  } else {
    EXPECT_NO_THROW(run_task_farm(cluster, farm));
  }
}

// Results every rank needs: placed once per task on every rank, each the task's own.
TEST(TaskFarm, EverywhereGivesEveryRankEveryResult) {
  Cluster& cluster = world_cluster();
  for (const std::size_t count : {std::size_t(0), std::size_t(3), std::size_t(150)}) {
    std::vector<std::vector<uint64_t>> placed(count);
    run_task_farm_everywhere(
        cluster, count,
        [](std::size_t task) {
          // Results of different sizes, one of them empty.
          ByteWriter writer;
          std::vector<uint64_t> values(task % 7);
          std::iota(values.begin(), values.end(), task * 100);
          writer.put_array(values);
          return writer.take();
        },
        [&](std::size_t task, std::span<const std::byte> result) {
          ASSERT_LT(task, count);
          EXPECT_TRUE(placed[task].empty()) << "placed twice: task " << task;
          placed[task] = ByteReader(result).get_array<uint64_t>();
        });
    for (std::size_t task = 0; task < count; ++task) {
      ASSERT_EQ(placed[task].size(), task % 7) << "rank " << cluster.rank() << " task " << task;
      for (std::size_t k = 0; k < placed[task].size(); ++k) EXPECT_EQ(placed[task][k], task * 100 + k);
    }
  }
}

// With `again`, rank 0 keeps no copy of the results and rebuilds them to pass on: every rank
// still places the bytes work made.
TEST(TaskFarm, EverywhereRebuildsResultsOnRankZero) {
  Cluster& cluster = world_cluster();
  const std::size_t count = 40;
  std::vector<uint64_t> placed(count, 0);
  std::size_t rebuilt = 0;
  run_task_farm_everywhere(
      cluster, count, [](std::size_t task) { return number_bytes(task * 7 + 3); },
      [&](std::size_t task, std::span<const std::byte> result) { placed[task] = read_number(result); },
      [&](std::size_t task) {
        ++rebuilt;
        return number_bytes(placed[task]);
      });
  for (std::size_t task = 0; task < count; ++task)
    EXPECT_EQ(placed[task], task * 7 + 3) << "rank " << cluster.rank();
  EXPECT_EQ(rebuilt, cluster.distributed() && cluster.root() ? count : 0u);
}

// The meshless transfer matrix S built by rows across the ranks is, on every rank, the matrix
// one process builds; past its entry limit it is refused on every rank.
TEST(TransferMatrix, RowsAcrossRanksAreTheSingleProcessRows) {
  Cluster& cluster = world_cluster();
  const std::unique_ptr<Scene> scene = load_scene_file(CANDELA_SOURCE_DIR "/scenes/cornell-box.json");
  SiteSamplingSettings sampling;
  sampling.grid = 24;
  sampling.rounds = 2;
  const SiteSet sites = sample_sites(*scene, sampling);
  ASSERT_GT(sites.sites.size(), 100u);
  const MeshlessBasis basis(sites.sites, sites.radius, BasisKind::normalized);
  TransferSettings settings;
  settings.gather_rays = 16;  // what is shared is the test, not the rows' precision
  const TransferMatrix alone = compute_transfer_matrix(*scene, sites, basis, sites.effective_area, settings);
  const TransferMatrix shared =
      compute_transfer_matrix(*scene, sites, basis, sites.effective_area, settings, &cluster);
  ASSERT_EQ(shared.S.rows(), alone.S.rows());
  ASSERT_EQ(shared.entries(), alone.entries());
  EXPECT_EQ(shared.visibility_rays, alone.visibility_rays);
  EXPECT_EQ(shared.far_field_scale, alone.far_field_scale);
  for (Eigen::Index j = 0; j < alone.S.outerSize(); ++j) {
    ASSERT_EQ(shared.S.outerIndexPtr()[j], alone.S.outerIndexPtr()[j]) << "row " << j;
  }
  for (std::size_t e = 0; e < alone.entries(); ++e) {
    ASSERT_EQ(shared.S.innerIndexPtr()[e], alone.S.innerIndexPtr()[e]) << "entry " << e;
    ASSERT_EQ(shared.S.valuePtr()[e], alone.S.valuePtr()[e]) << "entry " << e;  // bit for bit
  }
  TransferSettings limited = settings;
  limited.max_entries = alone.entries() / 3;
  EXPECT_THROW(compute_transfer_matrix(*scene, sites, basis, sites.effective_area, limited, &cluster),
               std::invalid_argument);
}

TEST(Cluster, CollectivesAgree) {
  Cluster& cluster = world_cluster();
  std::vector<uint64_t> counts{1, uint64_t(cluster.rank())};
  cluster.sum(counts);
  const auto n = uint64_t(cluster.size());
  EXPECT_EQ(counts[0], n);
  EXPECT_EQ(counts[1], n * (n - 1) / 2);
  std::vector<double> values{0.5};
  cluster.sum(values);
  EXPECT_EQ(values[0], 0.5 * double(n));
  EXPECT_TRUE(cluster.all(true));
  EXPECT_FALSE(cluster.all(cluster.rank() != 0));
  EXPECT_EQ(cluster.any(cluster.rank() == cluster.size() - 1), true);
  EXPECT_FALSE(cluster.any(false));
  // A broadcast of a few megabytes arrives whole and exact.
  Bytes bytes;
  if (cluster.root()) {
    bytes.resize(3u << 20);
    for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = std::byte(i * 31 % 251);
  }
  cluster.broadcast(bytes);
  ASSERT_EQ(bytes.size(), 3u << 20);
  bool exact = true;
  for (std::size_t i = 0; i < bytes.size(); ++i) exact = exact && bytes[i] == std::byte(i * 31 % 251);
  EXPECT_TRUE(exact);
  if (cluster.distributed()) {
    EXPECT_GT(cluster.volume().collective_bytes, 3u << 20);
  }
}

// Ctrl-C on one rank reaches all of them at the next agreement.
TEST(Cluster, CancellationOnOneRankStopsAll) {
  Cluster& cluster = world_cluster();
  reset_cancellation();
  EXPECT_FALSE(cancelled_anywhere(cluster));
  if (cluster.rank() == cluster.size() - 1) request_cancellation();
  EXPECT_TRUE(cancelled_anywhere(cluster));
  EXPECT_TRUE(cancel_requested());
  reset_cancellation();
}

// Rank 0's failure stops the others with PeerFailure; its success lets all go on.
TEST(Cluster, RootOutcomeIsSettledEverywhere) {
  Cluster& cluster = world_cluster();
  EXPECT_NO_THROW(settle_root_outcome(cluster, nullptr));
  std::exception_ptr error;
  if (cluster.root()) error = std::make_exception_ptr(std::invalid_argument("bad checkpoint"));
  if (cluster.root()) {
    EXPECT_THROW(settle_root_outcome(cluster, error), std::invalid_argument);
  } else {
    EXPECT_THROW(settle_root_outcome(cluster, error), PeerFailure);
  }
}

TEST(Cluster, LaunchIsRecognised) {
  Cluster& cluster = world_cluster();
  EXPECT_EQ(launched_rank_count(), cluster.size());
  EXPECT_GE(cluster.rank(), 0);
  EXPECT_LT(cluster.rank(), cluster.size());
}

}  // namespace
}  // namespace candela

int main(int argc, char** argv) {
  candela::MpiSession session(argc, argv);  // MPI only when launched as several ranks
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
