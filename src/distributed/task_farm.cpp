#include "distributed/task_farm.h"

#include <cstring>
#include <exception>
#include <mutex>
#include <optional>
#include <thread>

#include "distributed/backoff.h"

namespace candela {

namespace {

// What a message of the farm is, its first byte. A farm's messages carry two tags of its own
// (farm_tags): the next farm's requests, sent by a rank that finished this one early, wait for it.
enum Kind : uint8_t {
  kRequest = 1,  // a worker wants a task
  kResult = 2,   // task number, result bytes; also asks for the next task
  kTask = 3,     // task number, input bytes
  kNoMore = 4,   // no task for this request
};

struct FarmTags {
  int to_coordinator, to_worker;
};

FarmTags farm_tags(Cluster& cluster) {
  const auto base =
      1000 + 2 * static_cast<int>(cluster.next_exchange() % 8000);  // below MPI's least tag bound, 32767
  return {base, base + 1};
}

// How many requests a worker keeps outstanding: the task it works on and the next one.
constexpr int kRequestsInFlight = 2;

// The kind, a task number, then the payload.
Bytes message_of(Kind kind, std::size_t task = 0, std::span<const std::byte> payload = {}) {
  Bytes bytes(1 + sizeof(uint64_t) + payload.size());
  bytes[0] = std::byte{kind};
  const uint64_t number = task;
  std::memcpy(bytes.data() + 1, &number, sizeof number);
  if (!payload.empty()) std::memcpy(bytes.data() + 1 + sizeof number, payload.data(), payload.size());
  return bytes;
}

Kind kind_of(const Bytes& bytes) {
  if (bytes.size() < 1 + sizeof(uint64_t))
    throw std::runtime_error("task farm: a message shorter than its header");
  return static_cast<Kind>(bytes[0]);
}

std::size_t number_of(const Bytes& bytes) {
  return ByteReader(std::span<const std::byte>(bytes).subspan(1)).get<uint64_t>();
}

std::span<const std::byte> payload_of(const Bytes& bytes) {
  return std::span<const std::byte>(bytes).subspan(1 + sizeof(uint64_t));
}

TaskFarmReport run_alone(const TaskFarm& farm) {
  TaskFarmReport report;
  report.tasks_by_rank.assign(1, 0);
  for (std::size_t task = 0; task < farm.task_count; ++task) {
    if (farm.stop && farm.stop()) break;
    const Bytes input = farm.input ? farm.input(task) : Bytes();
    farm.collect(task, farm.work(task, input));
    ++report.tasks_by_rank[0];
    ++report.tasks_done;
  }
  return report;
}

// Rank 0: the coordinator (this thread) and a working thread that share the next task number.
TaskFarmReport run_coordinator(Cluster& cluster, const TaskFarm& farm, const FarmTags& tags) {
  TaskFarmReport report;
  report.tasks_by_rank.assign(static_cast<std::size_t>(cluster.size()), 0);
  std::mutex mutex;  // guards next, stopped, farm.input, farm.collect and local_results
  std::size_t next = 0;
  bool stopped = false;
  std::vector<std::pair<std::size_t, Bytes>> local_results;
  // The next task number, or none; with the mutex held.
  const auto take_task = [&]() -> std::optional<std::size_t> {
    if (!stopped && farm.stop && farm.stop()) stopped = true;
    if (stopped || next >= farm.task_count) return std::nullopt;
    return next++;
  };
  std::exception_ptr local_error;
  bool local_finished = false;
  std::thread worker([&] {
    try {
      for (;;) {
        std::size_t task;
        Bytes input;
        {
          std::lock_guard lock(mutex);
          const std::optional<std::size_t> taken = take_task();
          if (!taken) break;
          task = *taken;
          if (farm.input) input = farm.input(task);
        }
        Bytes result = farm.work(task, input);
        std::lock_guard lock(mutex);
        local_results.emplace_back(task, std::move(result));
      }
    } catch (...) {
      std::lock_guard lock(mutex);
      local_error = std::current_exception();
      stopped = true;
    }
    std::lock_guard lock(mutex);
    local_finished = true;
  });

  std::exception_ptr collect_error;
  const auto collect = [&](std::size_t task, Bytes result, int rank) {
    if (collect_error) return;  // after a failure the rest is only drained
    try {
      farm.collect(task, std::move(result));
      ++report.tasks_by_rank[static_cast<std::size_t>(rank)];
      ++report.tasks_done;
    } catch (...) {
      collect_error = std::current_exception();
      stopped = true;
    }
  };
  // Each worker holds kRequestsInFlight requests until it is told "no more" that many times.
  int open_requests = (cluster.size() - 1) * kRequestsInFlight;
  const auto answer = [&](int rank) {
    std::optional<std::size_t> task;
    Bytes input;
    {
      std::lock_guard lock(mutex);
      task = take_task();
      if (task && farm.input) input = farm.input(*task);
    }
    if (task) {
      cluster.send(rank, tags.to_worker, message_of(kTask, *task, input));
    } else {
      cluster.send(rank, tags.to_worker, message_of(kNoMore));
      --open_requests;
    }
  };
  Backoff idle;
  try {
    for (;;) {
      bool busy = false;
      {
        std::vector<std::pair<std::size_t, Bytes>> finished;
        bool done_locally;
        {
          std::lock_guard lock(mutex);
          finished.swap(local_results);
          done_locally = local_finished;
        }
        for (auto& [task, result] : finished) {
          std::lock_guard lock(mutex);
          collect(task, std::move(result), 0);
          busy = true;
        }
        if (done_locally && open_requests == 0) {
          std::lock_guard lock(mutex);
          if (local_results.empty()) break;
        }
      }
      ClusterMessage message;
      if (cluster.try_receive(tags.to_coordinator, message)) {
        busy = true;
        const Kind kind = kind_of(message.bytes);
        if (kind == kResult) {
          std::lock_guard lock(mutex);
          collect(number_of(message.bytes),
                  Bytes(payload_of(message.bytes).begin(), payload_of(message.bytes).end()), message.source);
        } else if (kind != kRequest) {
          throw std::runtime_error("task farm: unexpected message kind " + std::to_string(int(kind)));
        }
        answer(message.source);
      }
      if (busy) {
        idle.reset();
      } else {
        idle.pause();
      }
    }
  } catch (...) {  // a broken message: stop the working thread before leaving
    {
      std::lock_guard lock(mutex);
      stopped = true;
    }
    worker.join();
    throw;
  }
  worker.join();
  cluster.flush_sends();
  if (local_error) std::rethrow_exception(local_error);
  if (collect_error) std::rethrow_exception(collect_error);
  return report;
}

// Ranks other than 0: ask, work, send the result (asking again), until told "no more" for every
// outstanding request.
void run_worker(Cluster& cluster, const TaskFarm& farm, const FarmTags& tags) {
  for (int k = 0; k < kRequestsInFlight; ++k) cluster.send(0, tags.to_coordinator, message_of(kRequest));
  int open_requests = kRequestsInFlight;
  while (open_requests > 0) {
    const ClusterMessage message = cluster.receive(tags.to_worker);
    --open_requests;
    const Kind kind = kind_of(message.bytes);
    if (kind == kNoMore) continue;
    if (kind != kTask)
      throw std::runtime_error("task farm: unexpected message kind " + std::to_string(int(kind)));
    const std::size_t task = number_of(message.bytes);
    const Bytes result = farm.work(task, payload_of(message.bytes));
    cluster.send(0, tags.to_coordinator, message_of(kResult, task, result));
    ++open_requests;
  }
  cluster.flush_sends();
}

}  // namespace

TaskFarmReport run_task_farm(Cluster& cluster, const TaskFarm& farm) {
  if (!cluster.distributed()) return run_alone(farm);
  const FarmTags tags = farm_tags(cluster);
  if (cluster.root()) return run_coordinator(cluster, farm, tags);
  run_worker(cluster, farm, tags);
  return {};
}

void run_task_farm_everywhere(
    Cluster& cluster, std::size_t task_count, const std::function<Bytes(std::size_t task)>& work,
    const std::function<void(std::size_t task, std::span<const std::byte> result)>& place,
    const std::function<Bytes(std::size_t task)>& again) {
  std::vector<Bytes> results(cluster.distributed() && cluster.root() && !again ? task_count : 0);
  TaskFarm farm;
  farm.task_count = task_count;
  farm.work = [&](std::size_t task, std::span<const std::byte>) { return work(task); };
  farm.collect = [&](std::size_t task, Bytes result) {
    place(task, result);
    if (cluster.distributed() && !again) results[task] = std::move(result);
  };
  run_task_farm(cluster, farm);
  if (!cluster.distributed()) return;
  // Rank 0 sends the results in batches of about 64 MiB (one broadcast each), freeing them as
  // they go, so the copy it keeps for sending stays bounded.
  constexpr std::size_t kBatchBytes = std::size_t{64} << 20;
  std::size_t first = 0;
  while (first < task_count) {
    Bytes batch;
    std::size_t end = first;
    if (cluster.root()) {
      ByteWriter writer;
      std::size_t size = 0;
      while (end < task_count && (end == first || size < kBatchBytes)) {
        Bytes result = again ? again(end) : std::move(results[end]);
        size += result.size();
        writer.put_array(result);
        if (!again) Bytes().swap(results[end]);
        ++end;
      }
      writer.put<uint64_t>(end);
      batch = writer.take();
    }
    cluster.broadcast(batch);
    if (!cluster.root()) {
      // The batch's last 8 bytes say where it ends.
      ByteReader tail(std::span<const std::byte>(batch).subspan(batch.size() - sizeof(uint64_t)));
      end = tail.get<uint64_t>();
      ByteReader reader(std::span<const std::byte>(batch).first(batch.size() - sizeof(uint64_t)));
      for (std::size_t task = first; task < end; ++task) {
        const std::vector<std::byte> result = reader.get_array<std::byte>();
        place(task, result);
      }
    }
    first = end;
  }
}

}  // namespace candela
