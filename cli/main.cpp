// candela: one executable, thin sub-commands over the core library (SPEC "Product surface").
#include <fmt/format.h>

#include <exception>
#include <iostream>
#include <optional>

#include "commands.h"
#include "distributed/cluster.h"
#include "util/error.h"

namespace candela::cli {

// Under mpirun the ranks other than 0 had the same input as rank 0: they leave bad input to it.
void print_error(const std::string& message) {
  if (world_cluster().root()) std::cerr << "candela: error: " << message << "\n";
}

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
  // Under mpirun with several ranks, MPI starts here (distributed/cluster.h); otherwise nothing of
  // it is touched and the process runs alone.
  std::optional<candela::MpiSession> session;
  try {
    session.emplace(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "candela: error: " << e.what() << "\n";
    return 2;
  }
  candela::Cluster& cluster = candela::world_cluster();
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
  candela::cli::add_falsecolor_command(app, run);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (!cluster.root()) return e.get_exit_code() == 0 ? 0 : 2;  // rank 0 prints it
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  }
  if (cluster.distributed() && !app.got_subcommand("render")) {
    candela::cli::print_error(app.get_subcommands().front()->get_name() +
                              " runs in one process: start it without mpirun (only render is distributed)");
    return 2;
  }
  try {
    return run();
  } catch (const candela::PeerFailure& e) {
    return e.exit_code();  // the rank that failed said why
  } catch (const std::exception& e) {
    if (!cluster.distributed()) {
      candela::cli::print_error(e.what());
      return 1;
    }
    // Once the ranks work together an error on one would leave the others waiting: it ends all.
    std::cerr << fmt::format("candela: error (rank {} of {}): {}\n", cluster.rank(), cluster.size(),
                             e.what());
    candela::abort_all_ranks(1);
  }
}
