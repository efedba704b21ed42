#include "util/progress.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <string>

namespace candela {
namespace {

std::string run_to_file(bool quiet) {
  std::FILE* file = std::tmpfile();
  {
    ProgressReporter progress("render", 20, "tiles", quiet, file);
    for (int i = 0; i < 20; ++i) progress.advance();
  }
  std::rewind(file);
  std::string text;
  char buffer[256];
  while (std::fgets(buffer, sizeof buffer, file)) text += buffer;
  std::fclose(file);
  return text;
}

TEST(Progress, PlainLinesWhenNotATerminal) {
  const std::string text = run_to_file(false);
  // One line per 10% step, no carriage returns.
  EXPECT_NE(text.find("render: 10% (2/20 tiles"), std::string::npos) << text;
  EXPECT_NE(text.find("render: 100% (20/20 tiles"), std::string::npos) << text;
  EXPECT_EQ(text.find('\r'), std::string::npos);
  int lines = 0;
  for (char c : text) lines += c == '\n';
  EXPECT_EQ(lines, 10);
}

TEST(Progress, DetailFollowsTheCount) {
  // The radiosity solver shows its unshot fraction this way.
  std::FILE* file = std::tmpfile();
  {
    ProgressReporter progress("radiosity", 10, "per mille", false, file);
    progress.set_detail("unshot 4.5%");
    progress.advance(10);
  }
  std::rewind(file);
  char buffer[256];
  std::string text;
  while (std::fgets(buffer, sizeof buffer, file)) text += buffer;
  std::fclose(file);
  EXPECT_NE(text.find("radiosity: 100% (10/10 per mille, unshot 4.5%, "), std::string::npos) << text;
}

TEST(Progress, QuietPrintsNothing) {
  EXPECT_TRUE(run_to_file(true).empty());
}

TEST(Progress, ConvergenceProgressIsLogarithmic) {
  EXPECT_DOUBLE_EQ(convergence_progress(1.0, 0.001), 0.0);
  EXPECT_NEAR(convergence_progress(0.1, 0.001), 1.0 / 3, 1e-12);
  EXPECT_NEAR(convergence_progress(0.01, 0.001), 2.0 / 3, 1e-12);
  EXPECT_DOUBLE_EQ(convergence_progress(0.001, 0.001), 1.0);
  EXPECT_DOUBLE_EQ(convergence_progress(0.0, 0.001), 1.0);
  // Threshold 0 left the bar at 0 all the way; it is measured against 10⁻¹⁵.
  EXPECT_NEAR(convergence_progress(1e-6, 0.0), 0.4, 1e-12);
  EXPECT_DOUBLE_EQ(convergence_progress(0.0, 0.0), 1.0);
  EXPECT_DOUBLE_EQ(convergence_progress(1.0, 0.0), 0.0);
}

}  // namespace
}  // namespace candela
