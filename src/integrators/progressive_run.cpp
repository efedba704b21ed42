#include "integrators/progressive_run.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <utility>

#include "integrators/distributed_tiles.h"

namespace candela {

ProgressiveRun::ProgressiveRun(const RenderRequest& request, std::string fingerprint, RunLimits limits)
    : request_(request),
      cluster_(several_ranks(request)),
      fingerprint_(std::move(fingerprint)),
      limits_(limits) {
  if (request.checkpoint_interval > 0) limits_.checkpoint_interval = request.checkpoint_interval;
  // Rank 0 alone hands out checkpoints.
  if (request.checkpoint && root())
    checkpoints_ = CheckpointSchedule(request.save_checkpoint, limits_.checkpoint_interval);
}

void ProgressiveRun::start(uint64_t first_step, std::string_view label, std::string_view unit,
                           std::string_view count_name) {
  first_step_ = first_step;
  count_name_ = count_name;
  // Under a time limit alone the line counts seconds.
  const bool by_steps = limits_.steps > 0;
  unit_ = unit;
  const uint64_t total = by_steps ? limits_.steps - std::min(first_step, limits_.steps)
                                  : static_cast<uint64_t>(std::ceil(limits_.seconds));
  progress_ = std::make_unique<ProgressReporter>(
      std::string(label), total, by_steps ? std::string(unit) : "s", request_.quiet || !root());
  timer_ = Stopwatch();
}

void ProgressiveRun::step_done(uint64_t steps, const std::function<Film()>& image) {
  if (request_.on_progress) request_.on_progress({unit_, steps, std::nullopt, image});
  progress_->set_detail(fmt::format("{} {}", steps, count_name_));
  if (limits_.steps > 0) {
    progress_->advance();
  } else {
    const auto whole = static_cast<uint64_t>(timer_.seconds());
    const auto total = static_cast<uint64_t>(std::ceil(limits_.seconds));
    if (whole > seconds_reported_) {
      progress_->advance(std::min(whole, total) - std::min(seconds_reported_, total));
      seconds_reported_ = whole;
    }
  }
}

bool ProgressiveRun::more_steps(uint64_t steps) const {
  if (limits_.steps > 0 && steps >= limits_.steps) return false;
  return !(limits_.seconds > 0 && timer_.seconds() >= limits_.seconds);
}

void ProgressiveRun::report(uint64_t steps, double seconds_before, bool interrupted, nlohmann::json& facts,
                            RunStatistics& statistics) const {
  facts[count_name_] = steps;
  facts[fmt::format("{}_this_run", unit_)] = steps - first_step_;
  facts["checkpoints_written"] = checkpoints_.written();
  facts["seconds_all_runs"] = seconds_before + timer_.seconds();
  if (resumed_) facts[fmt::format("resumed_from_{}", count_name_)] = first_step_;
  if (interrupted) {  // Ctrl-C: what the state holds, which the checkpoint holds too
    statistics.extra["interrupted"] = true;
    statistics.extra["completed"] = fmt::format("{} {}{}", steps - first_step_, unit_,
                                                first_step_ > 0 ? fmt::format(" ({} in all)", steps) : "");
  }
}

}  // namespace candela
