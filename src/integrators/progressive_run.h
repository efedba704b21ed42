// The run of a progressive method, apart from the method's own work (SPEC §12, §15; the split of
// pbrt-v4's ImageTileIntegrator, which drives, from the integrator that traces): the checkpoint
// to resume from (read by rank 0 alone and checked against the fingerprint of the scene and the
// settings that shape the work), the checkpoints handed out while it runs and at its end, the
// progress line, the request's per-step callback (the error log, a test's stop) and the facts
// every progressive run reports. The path tracer's passes (integrators/pass_method.h) and
// progressive radiosity's shots (integrators/radiosity_method.cpp) both run through it.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "distributed/cluster.h"
#include "integrators/method.h"
#include "io/checkpoint_schedule.h"
#include "util/error.h"
#include "util/progress.h"
#include "util/statistics.h"

namespace candela {

// How far a run goes: the settings that say only that, so that a run resumed with more steps or
// more time goes on from a checkpoint (and one with another sampler is refused by the fingerprint).
struct RunLimits {
  uint64_t steps = 0;               // 0: no limit
  std::string steps_setting;        // the setting that gives it ("path.spp"), for errors
  double seconds = 0;               // 0: no limit
  double checkpoint_interval = 60;  // seconds between checkpoints; the request's, when it sets one
};

class ProgressiveRun {
 public:
  // fingerprint: what ties a checkpoint to the work (the request's part and the method's).
  ProgressiveRun(const RenderRequest& request, std::string fingerprint, RunLimits limits);

  // The request's cluster when it has several ranks; null on one process.
  Cluster* cluster() const { return cluster_; }
  bool root() const { return !cluster_ || cluster_->root(); }
  const std::string& fingerprint() const { return fingerprint_; }
  const RunLimits& limits() const { return limits_; }
  const RenderRequest& request() const { return request_; }

  // The state of the request's checkpoint, when it has one: read by rank 0 alone with `unseal`,
  // its fingerprint compared with this run's and `check` run on it (an InputError naming the
  // checkpoint's source, where: {source}). An error on rank 0 stops every rank (PeerFailure on
  // the others). everywhere: the sealed bytes are sent to the other ranks, which unseal them too;
  // otherwise they are given none.
  template <typename State>
  std::optional<State> resume(const std::function<State(const SealedCheckpoint&)>& unseal,
                              const std::function<void(const State&, const SourceLocation&)>& check,
                              bool everywhere);

  // Starts the progress line of the steps from `first_step` on (`label`: the method's name; the
  // unit what a step is, or seconds under a time limit alone), and the clock of the time limit.
  // count_name: the steps of all runs in the facts and the progress line ("spp").
  void start(uint64_t first_step, std::string_view label, std::string_view unit, std::string_view count_name);
  // After each whole step, with the steps done so far in all runs (one process, or rank 0 after a
  // round): the progress line and the request's on_progress (`image`: the image of the state
  // reached).
  void step_done(uint64_t steps, const std::function<Film()>& image);
  // Whether another step may start after `steps`: the step limit and the time limit.
  bool more_steps(uint64_t steps) const;
  double seconds() const { return timer_.seconds(); }
  void finish_progress() { progress_->finish(); }

  // Hands out the state (rank 0, with RenderRequest::checkpoint): between steps every
  // checkpoint_interval seconds while steps remain, and the final state.
  CheckpointSchedule& checkpoints() { return checkpoints_; }

  // The facts of every progressive run, into `facts` under the method's names: the steps of all
  // runs (count_name), of this run, where it resumed from, the checkpoints written and the time
  // of all runs (`seconds_before`: of the runs before); and when interrupted, the "interrupted"
  // and "completed" facts into `statistics`.
  void report(uint64_t steps, double seconds_before, bool interrupted, nlohmann::json& facts,
              RunStatistics& statistics) const;

 private:
  const RenderRequest& request_;
  Cluster* cluster_;
  std::string fingerprint_;
  RunLimits limits_;
  CheckpointSchedule checkpoints_;
  std::unique_ptr<ProgressReporter> progress_;
  Stopwatch timer_;
  std::string unit_, count_name_;
  uint64_t first_step_ = 0, seconds_reported_ = 0;
  bool resumed_ = false;
};

// Rank 0 unseals and checks; every rank learns the outcome (distributed/cluster.h).
template <typename State>
std::optional<State> ProgressiveRun::resume(
    const std::function<State(const SealedCheckpoint&)>& unseal,
    const std::function<void(const State&, const SourceLocation&)>& check, bool everywhere) {
  if (!request_.resume) return std::nullopt;
  std::optional<State> state;
  std::exception_ptr error;
  try {
    if (root()) {
      const SourceLocation where{request_.resume->source, 0, 0, {}};
      state = unseal(*request_.resume);
      if (state->fingerprint != fingerprint_)
        throw InputError(where, "the checkpoint was made for another scene or other settings (" +
                                    state->fingerprint + "), not this one (" + fingerprint_ + ")");
      if (check) check(*state, where);
    }
  } catch (...) {
    if (!cluster_) throw;
    error = std::current_exception();
  }
  if (cluster_) {
    settle_root_outcome(*cluster_, error);
    if (everywhere) {
      SealedCheckpoint sealed{request_.resume->source, root() ? request_.resume->bytes : Bytes()};
      cluster_->broadcast(sealed.bytes);
      if (!root()) state = unseal(sealed);
    }
  }
  resumed_ = true;
  return state;
}

}  // namespace candela
