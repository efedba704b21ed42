// One syntax for every option that takes several values: comma-separated
// (--accel bvh,embree), separated by spaces (--accel bvh embree), or the option repeated
// (--accel bvh --accel embree), in any mix.
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace candela::cli {

// `count` values exactly (--crop x0,y0,x1,y1: 4), or any number of them, at least one, when 0.
template <class Value>
CLI::Option* add_list_option(CLI::App* command, const std::string& names, std::vector<Value>& values,
                             const std::string& description, int count = 0) {
  CLI::Option* option = command->add_option(names, values, description)->delimiter(',');
  if (count > 0) return option->expected(count);
  return option->expected(1, -1);
}

}  // namespace candela::cli
