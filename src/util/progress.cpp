#include "util/progress.h"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>

namespace candela {

double convergence_progress(double remaining_fraction, double threshold) {
  // A threshold of 0 (radiosity runs until nothing is left to shoot or max_steps) is
  // measured against 10⁻¹⁵, about what double precision resolves of a total, not left at 0.
  if (!(threshold > 0)) threshold = 1e-15;
  if (remaining_fraction <= threshold || threshold >= 1) return 1.0;
  if (remaining_fraction >= 1) return 0.0;
  return std::clamp(std::log(remaining_fraction) / std::log(threshold), 0.0, 1.0);
}

ProgressReporter::ProgressReporter(std::string label, uint64_t total, std::string unit, bool quiet,
                                   std::FILE* stream)
    : label_(std::move(label)),
      unit_(std::move(unit)),
      total_(total),
      quiet_(quiet),
      terminal_(::isatty(::fileno(stream)) != 0),
      stream_(stream),
      start_(std::chrono::steady_clock::now()),
      last_print_(start_) {}

ProgressReporter::~ProgressReporter() {
  finish();
}

void ProgressReporter::advance(uint64_t amount) {
  const uint64_t done = done_.fetch_add(amount) + amount;
  if (quiet_) return;
  std::unique_lock lock(mutex_, std::try_to_lock);
  if (!lock.owns_lock()) return;  // someone is printing; the next advance will
  print(done, false);
}

void ProgressReporter::set_detail(std::string detail) {
  std::lock_guard lock(mutex_);
  detail_ = std::move(detail);
}

void ProgressReporter::finish() {
  std::lock_guard lock(mutex_);
  if (finished_) return;
  finished_ = true;
  if (!quiet_) print(done_.load(), true);
}

void ProgressReporter::print(uint64_t done, bool final_line) {
  const auto now = std::chrono::steady_clock::now();
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const int percent = total_ ? static_cast<int>(100.0 * done / total_) : 100;
  if (terminal_) {
    // Redraw at most ten times a second: a terminal is slow to scroll through thousands.
    if (!final_line && now - last_print_ < std::chrono::milliseconds(100)) return;
    constexpr int kWidth = 30;
    const int filled = total_ ? static_cast<int>(kWidth * done / total_) : kWidth;
    const double remaining = done > 0 ? elapsed * (double(total_) - done) / done : 0;
    fmt::print(stream_, "\r{} [{}{}] {:3d}% {}/{} {}{}{} {:.1f}s elapsed, {:.1f}s left ", label_,
               std::string(filled, '#'), std::string(kWidth - filled, ' '), percent, done, total_, unit_,
               detail_.empty() ? "" : ", ", detail_, elapsed, remaining);
    if (final_line) fmt::print(stream_, "\n");
  } else {
    // Plain lines: at every 10% step and at most every 5 s otherwise, never more often.
    const bool step = percent / 10 != last_percent_ / 10;
    if (!final_line && !step && now - last_print_ < std::chrono::seconds(5)) return;
    if (final_line && percent == last_percent_) return;
    fmt::print(stream_, "{}: {}% ({}/{} {}{}{}, {:.1f}s)\n", label_, percent, done, total_, unit_,
               detail_.empty() ? "" : ", ", detail_, elapsed);
  }
  std::fflush(stream_);
  last_percent_ = percent;
  last_print_ = now;
}

}  // namespace candela
