// Dynamic scheduling of independent tasks across the ranks: rank 0 hands out task
// numbers in order, one at a time, to whichever rank asks — so a slow rank (a busy node, a tile
// full of glass) takes fewer tasks instead of holding the others up — and renders tasks itself
// between answering. Results come back to rank 0.
//
//   rank 0   the calling thread answers requests and collects results; a second thread works on
//            tasks (its own parallelism is the work function's: TBB inside a task). Only the
//            calling thread calls MPI (MPI_THREAD_FUNNELED).
//   others   ask for two tasks at the start and, with each result, for one more: the next task
//            is on its way while the current one is worked on.
//
// On one process the tasks run in order on the calling thread. A task's result depends on the
// task alone, never on which rank ran it; that is what makes distributed images bit-identical.
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "distributed/cluster.h"
#include "io/byte_stream.h"

namespace candela {

struct TaskFarm {
  std::size_t task_count = 0;
  // Rank 0: what a task needs besides its number (empty function: nothing). May be called on
  // either of rank 0's threads, never at the same time as itself or collect.
  std::function<Bytes(std::size_t task)> input;
  // Every rank: does the task. On rank 0 it runs on the working thread.
  std::function<Bytes(std::size_t task, std::span<const std::byte> input)> work;
  // Rank 0: a task's result, once per task, in the order results arrive.
  std::function<void(std::size_t task, Bytes result)> collect;
  // Rank 0, asked before each task is handed out: true stops handing out (Ctrl-C). The tasks not
  // handed out are never collected.
  std::function<bool()> stop;
};

struct TaskFarmReport {
  std::vector<uint64_t> tasks_by_rank;  // rank 0: how many tasks each rank did
  std::size_t tasks_done = 0;           // rank 0: how many were collected
};

// Every rank calls it with the same task_count; returns when every handed-out task is collected.
// An exception from work or collect on rank 0 is rethrown once the others have stopped asking.
TaskFarmReport run_task_farm(Cluster& cluster, const TaskFarm& farm);

// Tasks whose results every rank needs (rows of a matrix that every rank then solves with): the
// farm, then rank 0 sends every result to every rank. place(task, result) is called once per task
// on every rank — on rank 0 as results arrive, elsewhere in task order.
// When `again` is given, rank 0 does not keep the results it collects: it asks again(task) for the
// same bytes (rebuilt from what place stored) when it sends them on, so it never holds the rows
// twice.
void run_task_farm_everywhere(
    Cluster& cluster, std::size_t task_count, const std::function<Bytes(std::size_t task)>& work,
    const std::function<void(std::size_t task, std::span<const std::byte> result)>& place,
    const std::function<Bytes(std::size_t task)>& again = {});

}  // namespace candela
