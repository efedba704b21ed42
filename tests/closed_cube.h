// A test scene's "shapes" array: the closed cube [0, 2]³ of six quads facing inward, each with the
// given material (a JSON object, e.g. {"kd": 0.6, "emission": 1}) — the furnace of the radiosity
// tests and the enclosure whose form-factor rows sum to 1.
#pragma once

#include <string>

namespace candela::testing {

inline std::string closed_cube_shapes(const std::string& material) {
  const std::string m = R"(, "material": )" + material + "}";
  return R"("shapes": [
      {"type": "quad", "corner": [0, 0, 0], "edge_u": [0, 0, 2], "edge_v": [2, 0, 0])" +
         m + R"(,
      {"type": "quad", "corner": [0, 2, 0], "edge_u": [2, 0, 0], "edge_v": [0, 0, 2])" +
         m + R"(,
      {"type": "quad", "corner": [0, 0, 0], "edge_u": [0, 2, 0], "edge_v": [0, 0, 2])" +
         m + R"(,
      {"type": "quad", "corner": [2, 0, 0], "edge_u": [0, 0, 2], "edge_v": [0, 2, 0])" +
         m + R"(,
      {"type": "quad", "corner": [0, 0, 0], "edge_u": [2, 0, 0], "edge_v": [0, 2, 0])" +
         m + R"(,
      {"type": "quad", "corner": [0, 0, 2], "edge_u": [0, 2, 0], "edge_v": [2, 0, 0])" +
         m + "]";
}

}  // namespace candela::testing
