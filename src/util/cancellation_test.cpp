#include "util/cancellation.h"

#include <gtest/gtest.h>

#include <csignal>

namespace candela {
namespace {

TEST(Cancellation, RequestAndReset) {
  reset_cancellation();
  EXPECT_FALSE(cancel_requested());
  request_cancellation();
  EXPECT_TRUE(cancel_requested());
  reset_cancellation();
  EXPECT_FALSE(cancel_requested());
}

TEST(Cancellation, TheHandlerOnlySetsTheFlag) {
  struct sigaction previous_int = {}, previous_term = {};
  sigaction(SIGINT, nullptr, &previous_int);
  sigaction(SIGTERM, nullptr, &previous_term);
  reset_cancellation();
  install_interrupt_handler();
  std::raise(SIGINT);  // handled synchronously on this thread: the process goes on
  EXPECT_TRUE(cancel_requested());
  reset_cancellation();
  std::raise(SIGTERM);
  EXPECT_TRUE(cancel_requested());
  reset_cancellation();
  // A second signal would end the test binary: put the previous handlers back instead.
  sigaction(SIGINT, &previous_int, nullptr);
  sigaction(SIGTERM, &previous_term, nullptr);
}

}  // namespace
}  // namespace candela
