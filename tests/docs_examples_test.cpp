// Every ```json block of docs/scene-format.md is a complete scene that loads.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "integrators/scene_loading.h"

namespace candela {
namespace {

TEST(DocsExamples, EveryJsonBlockLoads) {
  const std::string docs = std::string(CANDELA_SOURCE_DIR) + "/docs";
  std::ifstream in(docs + "/scene-format.md");
  ASSERT_TRUE(in) << "docs/scene-format.md is missing";
  std::string line, block;
  bool inside = false;
  int blocks = 0, line_number = 0, block_start = 0;
  while (std::getline(in, line)) {
    ++line_number;
    if (!inside && line == "```json") {
      inside = true;
      block.clear();
      block_start = line_number + 1;
    } else if (inside && line == "```") {
      inside = false;
      ++blocks;
      try {
        const auto scene =
            load_scene_text(block, "scene-format.md block at line " + std::to_string(block_start), docs);
        EXPECT_FALSE(scene->primitives.empty()) << "block at line " << block_start;
      } catch (const std::exception& e) {
        ADD_FAILURE() << e.what();
      }
    } else if (inside) {
      block += line + "\n";
    }
  }
  EXPECT_GE(blocks, 7);
}

}  // namespace
}  // namespace candela
