#include "io/checkpoint_schedule.h"

#include <utility>

namespace candela {

CheckpointSchedule::CheckpointSchedule(std::function<void(const Bytes& sealed)> save, double interval)
    : hands_out_(true), save_(std::move(save)), interval_(interval) {}

void CheckpointSchedule::between_steps(const std::function<Bytes()>& seal) {
  if (!hands_out_ || !save_ || since_checkpoint_.seconds() < interval_) return;
  ++written_;
  since_checkpoint_ = Stopwatch();
  save_(seal());
}

void CheckpointSchedule::finish(const std::function<Bytes()>& seal) {
  if (!hands_out_) return;
  ++written_;
  since_checkpoint_ = Stopwatch();
  final_state_ = seal();
}

}  // namespace candela
