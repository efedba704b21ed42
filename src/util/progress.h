// One progress reporter for every long phase (STYLE.md habit 7): a bar on a terminal, plain
// periodic lines otherwise, nothing when quiet. Thread-safe.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <mutex>
#include <string>

namespace candela {

// How far an iteration that stops at a threshold has come, on a log scale, for progress bars: 0 at
// a remaining fraction (radiosity's unshot flux, meshless's relative change) of 1, 1 at the
// threshold (log(fraction) / log(threshold), clamped to [0, 1]); 1 when threshold ≥ 1; a threshold
// of 0 (or below) counts as 10⁻¹⁵.
double convergence_progress(double remaining_fraction, double threshold);

class ProgressReporter {
 public:
  // unit names what is counted ("tiles").
  ProgressReporter(std::string label, uint64_t total, std::string unit, bool quiet,
                   std::FILE* stream = stderr);
  ~ProgressReporter();
  void advance(uint64_t amount = 1);
  // Advances to `done` when that is further than so far (a measure that only grows in steps, like
  // per mille of convergence); one caller at a time.
  void advance_to(uint64_t done) {
    const uint64_t so_far = done_.load();
    if (done > so_far) advance(done - so_far);
  }
  // A short text shown after the count from the next print on (e.g. "unshot 0.42%").
  void set_detail(std::string detail);
  void finish();

 private:
  void print(uint64_t done, bool final_line);
  std::string label_, unit_, detail_;
  uint64_t total_;
  bool quiet_, terminal_;
  std::FILE* stream_;
  std::atomic<uint64_t> done_{0};
  std::mutex mutex_;
  std::chrono::steady_clock::time_point start_, last_print_;
  int last_percent_ = -1;
  bool finished_ = false;
};

}  // namespace candela
