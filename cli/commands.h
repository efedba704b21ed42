// Sub-commands of the candela executable: each registers its options and returns the exit
// code (0 success, 1 failure, 2 bad input).
#pragma once

#include <CLI/CLI.hpp>
#include <functional>

namespace candela::cli {

// Adds the sub-command to app; *run is set to the function to call when it is chosen.
void add_render_command(CLI::App& app, std::function<int()>& run);
void add_info_command(CLI::App& app, std::function<int()>& run);
void add_bench_command(CLI::App& app, std::function<int()>& run);

// Prints "candela: error: ..." to stderr.
void print_error(const std::string& message);

}  // namespace candela::cli
