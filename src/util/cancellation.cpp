#include "util/cancellation.h"

#include <atomic>
#include <csignal>

namespace candela {

namespace {

// Lock-free, so that the handler may touch it (async-signal-safe).
std::atomic<bool> cancelled{false};
static_assert(std::atomic<bool>::is_always_lock_free);

extern "C" void on_interrupt(int signal_number) {
  if (cancelled.exchange(true)) {
    // The second one: the user means it. The default action ends the process.
    struct sigaction default_action = {};
    default_action.sa_handler = SIG_DFL;
    sigemptyset(&default_action.sa_mask);
    sigaction(signal_number, &default_action, nullptr);
    raise(signal_number);
  }
}

}  // namespace

void install_interrupt_handler() {
  struct sigaction action = {};
  action.sa_handler = on_interrupt;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;  // reads and writes in progress go on
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

bool cancel_requested() {
  return cancelled.load(std::memory_order_relaxed);
}

void request_cancellation() {
  cancelled.store(true, std::memory_order_relaxed);
}

void reset_cancellation() {
  cancelled.store(false, std::memory_order_relaxed);
}

}  // namespace candela
