// Sub-commands of the candela executable: each registers its options and returns the exit
// code (0 success, 1 failure, 2 bad input).
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <stdexcept>
#include <string>

namespace candela::cli {

// Adds the sub-command to app; *run is set to the function to call when it is chosen.
void add_render_command(CLI::App& app, std::function<int()>& run);
void add_info_command(CLI::App& app, std::function<int()>& run);
void add_bench_command(CLI::App& app, std::function<int()>& run);
void add_validate_command(CLI::App& app, std::function<int()>& run);
void add_compare_command(CLI::App& app, std::function<int()>& run);
void add_probe_command(CLI::App& app, std::function<int()>& run);
void add_report_command(CLI::App& app, std::function<int()>& run);
void add_falsecolor_command(CLI::App& app, std::function<int()>& run);
void add_convert_command(CLI::App& app, std::function<int()>& run);

// Prints "candela: error: ..." to stderr.
void print_error(const std::string& message);

// A command-line value that cannot be used (exit code 2).
class BadArgument : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Runs a sub-command: bad input (InputError, BadArgument) is printed and gives exit code 2;
// anything else propagates to main (exit code 1).
int run_reporting_bad_input(const std::function<int()>& command);

}  // namespace candela::cli
