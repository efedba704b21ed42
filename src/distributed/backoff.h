// How a rank waits for something another rank does: yield a few times, then sleep from 20 µs up
// to 1 ms while nothing arrives — a few microseconds of latency on a busy exchange, next to no
// processor time on a long wait (Open MPI's own blocking calls spin a core at 100 %, which the
// render threads of a rank on the same node would miss).
#pragma once

#include <algorithm>
#include <chrono>
#include <thread>

namespace candela {

class Backoff {
 public:
  void pause() {
    // The first waits only yield: a collective between ranks of one node completes in
    // microseconds, less than the shortest sleep the kernel gives (~60 µs).
    if (yields_ < 64) {
      ++yields_;
      std::this_thread::yield();
      return;
    }
    std::this_thread::sleep_for(std::chrono::microseconds(delay_));
    delay_ = std::min(delay_ * 2, 1000);
  }
  // Something arrived: the next wait starts short again.
  void reset() { *this = Backoff(); }

 private:
  int yields_ = 0;
  int delay_ = 20;
};

}  // namespace candela
