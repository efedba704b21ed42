#include "radiosity/form_factor_memory.h"

#include <gtest/gtest.h>

#include <string>

#include "radiosity/solvers.h"

namespace candela {
namespace {

TEST(RadiosityFormFactorMemory, TheLimitIsTheSettingOrHalfTheMachine) {
  RadiositySettings settings;
  EXPECT_EQ(form_factor_memory_limit(settings), default_gaussian_elimination_memory_limit());
  settings.memory_limit_mib = 3;
  EXPECT_EQ(form_factor_memory_limit(settings), 3u << 20);
  settings.memory_limit_mib = 2e13;  // beyond 2⁶⁴ bytes: no limit, not a wrapped-around 0
  EXPECT_EQ(form_factor_memory_limit(settings), UINT64_MAX);
  EXPECT_EQ(element_rows_bytes(1000, 300), 1000u * 300u * sizeof(float));
}

TEST(RadiosityFormFactorMemory, RefusalNamesWhatAndTheRemedyAndTheSetting) {
  RadiositySettings settings;
  settings.memory_limit_mib = 1;
  EXPECT_NO_THROW(check_form_factor_memory(1u << 20, settings, "the rows", "use fewer"));
  try {
    check_form_factor_memory((1u << 20) + 1, settings, "the rows of 5 elements",
                             "raise radiosity.patch_size");
    FAIL() << "expected SolverMemoryError";
  } catch (const SolverMemoryError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("the rows of 5 elements"), std::string::npos) << message;
    EXPECT_NE(message.find("raise radiosity.patch_size"), std::string::npos) << message;
    EXPECT_NE(message.find("radiosity.memory_limit_mib"), std::string::npos) << message;
    EXPECT_EQ(error.required_bytes(), (1u << 20) + 1);
    EXPECT_EQ(error.limit_bytes(), 1u << 20);
  }
}

}  // namespace
}  // namespace candela
