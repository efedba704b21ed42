// candela: one executable, thin sub-commands over the core library (SPEC "Product surface").
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <exception>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "build_version.h"
#include "commands.h"
#include "distributed/cluster.h"
#include "util/closest_word.h"
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

// "candela 0.1.0 (commit 1a2b3c4d5e6f; Embree, MPI)": the version, the checkout's commit at build
// time (+changes when it had uncommitted ones) and the optional parts built in.
std::string version_text() {
  std::vector<std::string> parts;
#ifdef CANDELA_HAVE_EMBREE
  parts.push_back("Embree");
#endif
#ifdef CANDELA_HAVE_MPI
  parts.push_back("MPI");
#endif
  std::string built =
      parts.empty() ? std::string("no Embree, no MPI") : fmt::format("{}", fmt::join(parts, ", "));
  return fmt::format("candela {} (commit {}; {})", CANDELA_VERSION, CANDELA_COMMIT, built);
}

// A first argument that is neither an option nor a sub-command: refused with the nearest
// sub-command when it looks like a slip of the fingers, and the list of them.
bool refuse_unknown_command(CLI::App& app, int argc, char** argv) {
  if (argc < 2 || argv[1][0] == '-') return false;
  std::vector<std::string> names;
  for (const CLI::App* command : app.get_subcommands([](CLI::App*) { return true; }))
    names.push_back(command->get_name());
  const std::string word = argv[1];
  if (std::find(names.begin(), names.end(), word) != names.end()) return false;
  const std::optional<std::string> nearest = closest_word(word, names);
  print_error(fmt::format("unknown command '{}'{} (commands: {})", word,
                          nearest ? " (did you mean " + *nearest + "?)" : std::string(),
                          fmt::join(names, ", ")));
  return true;
}

// CLI11's parse errors in Candela's form, naming the sub-command and the option: "candela: error:
// render: unknown option --thread (did you mean --threads?)", then where the options are listed.
std::string parse_failure_message(const CLI::App* app, const CLI::Error& error) {
  const std::vector<CLI::App*> parsed = app->get_subcommands();
  const CLI::App* command = parsed.empty() ? app : parsed.front();
  const std::string name = command == app ? std::string() : command->get_name();
  std::string message = error.what();
  if (dynamic_cast<const CLI::ExtrasError*>(&error)) {  // (its get_name() is the command's)
    std::vector<std::string> known;                     // every spelling of the command's options
    for (const CLI::Option* option : command->get_options()) {
      for (const std::string& long_name : option->get_lnames()) known.push_back("--" + long_name);
      for (const std::string& short_name : option->get_snames()) known.push_back("-" + short_name);
    }
    // What the sub-command did not take falls through to the top level.
    std::vector<std::string> extras = command->remaining();
    if (command != app && extras.empty()) extras = app->remaining();
    std::vector<std::string> problems;
    for (const std::string& extra : extras) {
      if (extra.empty() || extra[0] != '-') {
        problems.push_back("unexpected argument '" + extra + "'");
        continue;
      }
      const std::optional<std::string> nearest = closest_word(extra.substr(0, extra.find('=')), known);
      problems.push_back("unknown option " + extra + (nearest ? " (did you mean " + *nearest + "?)" : ""));
    }
    if (!problems.empty()) message = fmt::format("{}", fmt::join(problems, "; "));
  }
  return fmt::format("candela: error: {}{}\nRun 'candela {}--help' for the options.\n",
                     name.empty() ? "" : name + ": ", message, name.empty() ? "" : name + " ");
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
  candela::cli::add_convert_command(app, run);
  app.failure_message(candela::cli::parse_failure_message);
  app.set_version_flag("--version", candela::cli::version_text(),
                       "The version, commit and optional parts, then exit");
  if (candela::cli::refuse_unknown_command(app, argc, argv)) return 2;
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
