// The processes one run is split across (MPI, not a home-made protocol): the ranks of
// MPI_COMM_WORLD when Candela is built with MPI and started by an MPI launcher (mpirun), one
// process otherwise — the same binary runs either way.
//
// Every wait (a message, a broadcast, a reduction, the last sends) polls with a Backoff
// (distributed/backoff.h) rather than MPI's own blocking calls.
// What crosses is counted (CommunicationVolume), so docs/distributed.md can model larger runs.
#pragma once

#include <cstdint>
#include <exception>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/byte_stream.h"

namespace candela {

struct CommunicationVolume {
  uint64_t messages_sent = 0, bytes_sent = 0;
  uint64_t messages_received = 0, bytes_received = 0;
  uint64_t collectives = 0, collective_bytes = 0;  // broadcasts and reductions, payload counted once
  double waiting_seconds = 0;                      // polling for messages and collectives
};

struct ClusterMessage {
  int source = 0;
  int tag = 0;
  Bytes bytes;
};

class Cluster {
 public:
  // One process: rank 0 of 1.
  Cluster();
  ~Cluster();
  Cluster(const Cluster&) = delete;
  Cluster& operator=(const Cluster&) = delete;

  int rank() const { return rank_; }
  int size() const { return size_; }
  bool root() const { return rank_ == 0; }
  bool distributed() const { return size_ > 1; }
  const CommunicationVolume& volume() const { return volume_; }

  // Point to point (distributed only). send returns at once; the bytes are kept until delivered.
  void send(int destination, int tag, Bytes bytes);
  // A message with this tag from anyone, if one has arrived whole. Messages are taken in as they
  // arrive (MPI_Improbe, MPI_Imrecv), so a large one still being delivered holds up nothing else;
  // those of one source come out in the order sent.
  bool try_receive(int tag, ClusterMessage& message);
  // Waits for a message with this tag from anyone.
  ClusterMessage receive(int tag);
  // A number for the next exchange (a task farm): every rank counts the same exchanges in the same
  // order, so tags made from it keep one exchange's messages out of the next one's.
  uint64_t next_exchange() { return exchanges_++; }
  // Whether every rank knows of a failure and stops with it (settle_root_outcome): then an error
  // may end the command normally on each rank, without aborting the others.
  bool failure_agreed() const { return failure_agreed_; }
  void agree_failure() { failure_agreed_ = true; }
  // Waits until every send has been delivered.
  void flush_sends();

  // Collectives: every rank calls them in the same order. On one process they return at once.
  void broadcast(Bytes& bytes, int root = 0);
  void sum(std::vector<uint64_t>& values);  // every rank ends with the sums
  void sum(std::vector<double>& values);
  bool all(bool value);  // whether every rank passed true
  bool any(bool value);

  // The MPI start-up (MpiSession) makes the world cluster of a launched run.
  struct Implementation;
  explicit Cluster(std::unique_ptr<Implementation> implementation, int rank, int size);

 private:
  std::unique_ptr<Implementation> implementation_;
  int rank_ = 0, size_ = 1;
  uint64_t exchanges_ = 0;
  bool failure_agreed_ = false;
  CommunicationVolume volume_;
};

// The ranks the process was launched as, read from the launcher's environment (Open MPI's
// OMPI_COMM_WORLD_SIZE, PMI_SIZE of MPICH and Slurm's PMI-2); 1 when not launched by one.
int launched_rank_count();

// Starts MPI when the process was launched by mpirun with more than one rank (MPI_Init_thread,
// funnelled: only the main thread calls MPI) and ends it when it goes. Without a launcher nothing
// of MPI is touched. A launch of several ranks of a build without MPI is refused (each would
// render the whole image and write the same files): std::runtime_error.
class MpiSession {
 public:
  MpiSession(int& argc, char**& argv);
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;
};

// The cluster of this process: the MPI world while an MpiSession with several ranks lives,
// otherwise one process.
Cluster& world_cluster();

// Ends every rank of the run at once with this exit status (MPI_Abort; one process: exit): for an
// error on some ranks once they work together, when the others would wait for them for ever.
[[noreturn]] void abort_all_ranks(int exit_code);

// Thrown on the ranks that did nothing wrong when another rank failed where all of them must go on
// together (the failing rank reports the error): the command ends with exit_code, printing nothing.
class PeerFailure : public std::runtime_error {
 public:
  explicit PeerFailure(int exit_code) : std::runtime_error("another rank failed"), exit_code_(exit_code) {}
  int exit_code() const { return exit_code_; }

 private:
  int exit_code_;
};

// Whether Ctrl-C reached any rank (a collective): then every rank's flag is set, so that all of
// them stop at the same point. One process: cancel_requested().
bool cancelled_anywhere(Cluster& cluster);
// The same where a null cluster stands for this process alone.
bool cancelled_anywhere(Cluster* cluster);

// Where rank 0 alone did something that could fail (read a checkpoint): every rank calls it,
// rank 0 with what it caught (null: success). If rank 0 failed, it rethrows its error and the
// other ranks throw PeerFailure(2); otherwise it returns everywhere.
void settle_root_outcome(Cluster& cluster, std::exception_ptr root_error);

}  // namespace candela
