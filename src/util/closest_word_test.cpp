#include "util/closest_word.h"

#include <gtest/gtest.h>

namespace candela {
namespace {

TEST(ClosestWord, EditDistanceCountsInsertionsDeletionsAndSubstitutions) {
  EXPECT_EQ(edit_distance("", ""), 0u);
  EXPECT_EQ(edit_distance("render", "render"), 0u);
  EXPECT_EQ(edit_distance("rendr", "render"), 1u);    // one insertion
  EXPECT_EQ(edit_distance("renderr", "render"), 1u);  // one deletion
  EXPECT_EQ(edit_distance("rander", "render"), 1u);   // one substitution
  EXPECT_EQ(edit_distance("kitten", "sitting"), 3u);  // the textbook case
  EXPECT_EQ(edit_distance("", "probe"), 5u);
  EXPECT_EQ(edit_distance("probe", "info"), edit_distance("info", "probe"));
}

TEST(ClosestWord, SuggestsOnlyANearWord) {
  const std::vector<std::string> commands = {"render", "info", "bench", "validate", "compare", "probe"};
  EXPECT_EQ(closest_word("rendr", commands), "render");
  EXPECT_EQ(closest_word("prob", commands), "probe");
  EXPECT_EQ(closest_word("valdate", commands), "validate");
  EXPECT_EQ(closest_word("teleport", commands), std::nullopt);
  EXPECT_EQ(closest_word("x", commands), std::nullopt);
}

}  // namespace
}  // namespace candela
