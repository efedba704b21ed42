// candela: one executable, thin sub-commands over the core library (SPEC "Product surface").
#include <exception>
#include <iostream>

#include "commands.h"
#include "util/error.h"

namespace candela::cli {

void print_error(const std::string& message) { std::cerr << "candela: error: " << message << "\n"; }

int run_reporting_bad_input(const std::function<int()>& command) {
  try {
    return command();
  } catch (const InputError& e) {
    print_error(e.what());
    return 2;
  } catch (const BadArgument& e) {
    print_error(e.what());
    return 2;
  }
}

}  // namespace candela::cli

int main(int argc, char** argv) {
  CLI::App app{"Candela: global illumination renderer and lighting simulator"};
  app.require_subcommand(1);
  std::function<int()> run;
  candela::cli::add_render_command(app, run);
  candela::cli::add_info_command(app, run);
  candela::cli::add_bench_command(app, run);
  candela::cli::add_validate_command(app, run);
  candela::cli::add_compare_command(app, run);
  candela::cli::add_probe_command(app, run);
  candela::cli::add_report_command(app, run);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  }
  try {
    return run();
  } catch (const std::exception& e) {
    candela::cli::print_error(e.what());
    return 1;
  }
}
