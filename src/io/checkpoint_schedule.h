// When a progressive run hands out its state (SPEC §15: long runs checkpoint and resume): every
// `interval` seconds between steps while work remains, and once at the end — converged, out of
// steps or interrupted — kept for the caller. One schedule for every progressive method (the path
// tracer's passes, progressive radiosity's shots): the method says only how to seal its state.
#pragma once

#include <functional>
#include <optional>

#include "io/byte_stream.h"
#include "util/statistics.h"

namespace candela {

class CheckpointSchedule {
 public:
  // Hands out nothing (no --checkpoint, or a rank other than 0).
  CheckpointSchedule() = default;
  // save, when set, receives the sealed state every `interval` seconds; the final state is kept.
  CheckpointSchedule(std::function<void(const Bytes& sealed)> save, double interval);

  bool hands_out() const { return hands_out_; }
  // Between two steps, with work remaining: the state sealed and saved when the interval is up.
  void between_steps(const std::function<Bytes()>& seal);
  // The final state, sealed and kept for take_final.
  void finish(const std::function<Bytes()>& seal);
  std::optional<Bytes> take_final() { return std::move(final_state_); }
  // Checkpoints sealed so far, the final one included.
  int written() const { return written_; }

 private:
  bool hands_out_ = false;
  std::function<void(const Bytes& sealed)> save_;
  double interval_ = 0;
  Stopwatch since_checkpoint_;
  std::optional<Bytes> final_state_;
  int written_ = 0;
};

}  // namespace candela
