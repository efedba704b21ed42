#include "distributed/cluster.h"

#include <algorithm>
#include <chrono>
#include <climits>
#include <cstdlib>
#include <list>
#include <stdexcept>
#include <string>
#include <vector>

#include "distributed/backoff.h"
#include "util/cancellation.h"

#ifdef CANDELA_HAVE_MPI
#include <mpi.h>
#endif

namespace candela {

namespace {

[[maybe_unused]] double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// MPI counts are ints: larger payloads go in pieces.
[[maybe_unused]] constexpr std::size_t kLargestPiece = std::size_t{1} << 30;

std::logic_error single_process(const char* what) {
  return std::logic_error(std::string("Cluster::") + what + " needs several ranks");
}

int environment_integer(const char* name) {
  const char* value = std::getenv(name);
  if (!value || !*value) return 0;
  char* end = nullptr;
  const long number = std::strtol(value, &end, 10);
  return (*end == '\0' && number > 0 && number < INT_MAX) ? static_cast<int>(number) : 0;
}

}  // namespace

#ifdef CANDELA_HAVE_MPI

struct Cluster::Implementation {
  struct PendingSend {
    MPI_Request request;
    Bytes bytes;
  };
  std::list<PendingSend> sends;
  struct PendingReceive {
    MPI_Request request;
    ClusterMessage message;
  };
  std::list<PendingReceive> receives;

  // Frees the sends MPI has delivered.
  void reap() {
    for (auto it = sends.begin(); it != sends.end();) {
      int done = 0;
      MPI_Test(&it->request, &done, MPI_STATUS_IGNORE);
      it = done ? sends.erase(it) : std::next(it);
    }
  }
  void wait(MPI_Request& request, CommunicationVolume& volume) {
    const auto start = std::chrono::steady_clock::now();
    Backoff backoff;
    for (;;) {
      int done = 0;
      MPI_Test(&request, &done, MPI_STATUS_IGNORE);
      if (done) break;
      reap();
      backoff.pause();
    }
    volume.waiting_seconds += seconds_since(start);
  }
};

Cluster::Cluster(std::unique_ptr<Implementation> implementation, int rank, int size)
    : implementation_(std::move(implementation)), rank_(rank), size_(size) {}

void Cluster::send(int destination, int tag, Bytes bytes) {
  if (!implementation_) throw single_process("send");
  if (bytes.size() > static_cast<std::size_t>(INT_MAX))
    throw std::length_error("distributed message of " + std::to_string(bytes.size()) +
                            " bytes (at most 2 GiB)");
  implementation_->reap();
  auto& pending = implementation_->sends.emplace_back();
  pending.bytes = std::move(bytes);
  MPI_Isend(pending.bytes.data(), static_cast<int>(pending.bytes.size()), MPI_BYTE, destination, tag,
            MPI_COMM_WORLD, &pending.request);
  ++volume_.messages_sent;
  volume_.bytes_sent += pending.bytes.size();
}

bool Cluster::try_receive(int tag, ClusterMessage& message) {
  if (!implementation_) throw single_process("try_receive");
  Implementation& state = *implementation_;
  state.reap();
  // Start receiving every message that has come in...
  for (;;) {
    int arrived = 0;
    MPI_Message handle;
    MPI_Status status;
    MPI_Improbe(MPI_ANY_SOURCE, tag, MPI_COMM_WORLD, &arrived, &handle, &status);
    if (!arrived) break;
    int count = 0;
    MPI_Get_count(&status, MPI_BYTE, &count);
    auto& pending = state.receives.emplace_back();
    pending.message.source = status.MPI_SOURCE;
    pending.message.tag = status.MPI_TAG;
    pending.message.bytes.resize(static_cast<std::size_t>(count));
    MPI_Imrecv(pending.message.bytes.data(), count, MPI_BYTE, &handle, &pending.request);
  }
  // ... and hand out the first one delivered whole, none before an earlier one of its source.
  std::vector<int> sources_waiting;
  for (auto it = state.receives.begin(); it != state.receives.end(); ++it) {
    if (it->message.tag != tag) continue;
    if (std::find(sources_waiting.begin(), sources_waiting.end(), it->message.source) !=
        sources_waiting.end())
      continue;
    int done = 0;
    MPI_Test(&it->request, &done, MPI_STATUS_IGNORE);
    if (!done) {
      sources_waiting.push_back(it->message.source);
      continue;
    }
    message = std::move(it->message);
    state.receives.erase(it);
    ++volume_.messages_received;
    volume_.bytes_received += message.bytes.size();
    return true;
  }
  return false;
}

ClusterMessage Cluster::receive(int tag) {
  ClusterMessage message;
  const auto start = std::chrono::steady_clock::now();
  Backoff backoff;
  while (!try_receive(tag, message)) backoff.pause();
  volume_.waiting_seconds += seconds_since(start);
  return message;
}

void Cluster::flush_sends() {
  if (!implementation_) return;
  const auto start = std::chrono::steady_clock::now();
  Backoff backoff;
  for (implementation_->reap(); !implementation_->sends.empty(); implementation_->reap()) backoff.pause();
  volume_.waiting_seconds += seconds_since(start);
}

void Cluster::broadcast(Bytes& bytes, int root) {
  if (!implementation_) return;
  uint64_t size = bytes.size();
  MPI_Request request;
  MPI_Ibcast(&size, 1, MPI_UINT64_T, root, MPI_COMM_WORLD, &request);
  implementation_->wait(request, volume_);
  bytes.resize(size);
  for (std::size_t offset = 0; offset < size; offset += kLargestPiece) {
    const auto piece = static_cast<int>(std::min<std::size_t>(kLargestPiece, size - offset));
    MPI_Ibcast(bytes.data() + offset, piece, MPI_BYTE, root, MPI_COMM_WORLD, &request);
    implementation_->wait(request, volume_);
  }
  ++volume_.collectives;
  volume_.collective_bytes += size;
}

namespace {

template <typename T>
void all_reduce(std::vector<T>& values, MPI_Datatype type, MPI_Op op, Cluster::Implementation& implementation,
                CommunicationVolume& volume) {
  std::vector<T> result(values.size());
  MPI_Request request;
  MPI_Iallreduce(values.data(), result.data(), static_cast<int>(values.size()), type, op, MPI_COMM_WORLD,
                 &request);
  implementation.wait(request, volume);
  values.swap(result);
  ++volume.collectives;
  volume.collective_bytes += values.size() * sizeof(T);
}

}  // namespace

void Cluster::sum(std::vector<uint64_t>& values) {
  if (implementation_) all_reduce(values, MPI_UINT64_T, MPI_SUM, *implementation_, volume_);
}

void Cluster::sum(std::vector<double>& values) {
  if (implementation_) all_reduce(values, MPI_DOUBLE, MPI_SUM, *implementation_, volume_);
}

bool Cluster::all(bool value) {
  std::vector<int> flag{value ? 1 : 0};
  if (implementation_) all_reduce(flag, MPI_INT, MPI_MIN, *implementation_, volume_);
  return flag[0] != 0;
}

bool Cluster::any(bool value) {
  std::vector<int> flag{value ? 1 : 0};
  if (implementation_) all_reduce(flag, MPI_INT, MPI_MAX, *implementation_, volume_);
  return flag[0] != 0;
}

#else  // one process: every exchange is a logic error, every collective a no-op

struct Cluster::Implementation {};

Cluster::Cluster(std::unique_ptr<Implementation> implementation, int rank, int size)
    : implementation_(std::move(implementation)), rank_(rank), size_(size) {}
void Cluster::send(int, int, Bytes) {
  throw single_process("send");
}
bool Cluster::try_receive(int, ClusterMessage&) {
  throw single_process("try_receive");
}
ClusterMessage Cluster::receive(int) {
  throw single_process("receive");
}
void Cluster::flush_sends() {}
void Cluster::broadcast(Bytes&, int) {}
void Cluster::sum(std::vector<uint64_t>&) {}
void Cluster::sum(std::vector<double>&) {}
bool Cluster::all(bool value) {
  return value;
}
bool Cluster::any(bool value) {
  return value;
}

#endif

Cluster::Cluster() = default;
Cluster::~Cluster() = default;

int launched_rank_count() {
  // Open MPI's mpirun sets the first; MPICH's Hydra and Slurm's PMI-2 (srun --mpi=pmi2) the second.
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE"}) {
    const int size = environment_integer(name);
    if (size > 0) return size;
  }
  return 1;
}

namespace {

std::unique_ptr<Cluster>& world_slot() {
  static std::unique_ptr<Cluster> world;
  return world;
}

}  // namespace

Cluster& world_cluster() {
  std::unique_ptr<Cluster>& world = world_slot();
  if (!world) world = std::make_unique<Cluster>();
  return *world;
}

bool cancelled_anywhere(Cluster& cluster) {
  const bool cancelled = cluster.any(cancel_requested());
  if (cancelled && !cancel_requested()) request_cancellation();
  return cancelled;
}

bool cancelled_anywhere(Cluster* cluster) {
  return cluster ? cancelled_anywhere(*cluster) : cancel_requested();
}

void settle_root_outcome(Cluster& cluster, std::exception_ptr root_error) {
  Bytes outcome(1, std::byte{root_error ? uint8_t{1} : uint8_t{0}});
  cluster.broadcast(outcome);
  if (outcome[0] == std::byte{0}) return;
  cluster.agree_failure();
  if (cluster.root()) std::rethrow_exception(root_error);
  throw PeerFailure(2);
}

MpiSession::MpiSession([[maybe_unused]] int& argc, [[maybe_unused]] char**& argv) {
  const int launched = launched_rank_count();
  if (launched <= 1) return;
#ifdef CANDELA_HAVE_MPI
  int provided = 0;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
  if (provided < MPI_THREAD_FUNNELED) {
    MPI_Finalize();
    throw std::runtime_error("the MPI library does not allow threads (MPI_THREAD_FUNNELED)");
  }
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  world_slot() = std::make_unique<Cluster>(std::make_unique<Cluster::Implementation>(), rank, size);
#else
  throw std::runtime_error(
      "started as " + std::to_string(launched) +
      " MPI ranks, but this candela was built without MPI: every rank would render the whole "
      "image alone (install libopenmpi-dev and rebuild: scripts/install-deps.sh does)");
#endif
}

MpiSession::~MpiSession() {
#ifdef CANDELA_HAVE_MPI
  if (world_slot() && world_slot()->distributed()) {
    world_slot()->flush_sends();
    world_slot().reset();
    MPI_Finalize();
  }
#endif
}

void abort_all_ranks(int exit_code) {
#ifdef CANDELA_HAVE_MPI
  if (world_slot() && world_slot()->distributed()) MPI_Abort(MPI_COMM_WORLD, exit_code);
#endif
  std::exit(exit_code);
}

}  // namespace candela
