// candela validate CASE --out DIR [--quick] [--threads N]: the built-in validation cases (SPEC §13).
//   sphere-disc   the sphere over a disc of seed 002 chapter 7 (validate/sphere_disc.h): the
//                 reference by quadrature and the meshless FE solution for each basis at Δ = 3 and
//                 Δ = 1; CSV, PNG plots and errors.json in DIR (see docs/validation/sphere-disc.md).
//   form-factors  Howell's closed forms through the radiosity method at three refinements, and the
//                 furnace for every method (validate/form_factor_validation.h); CSV, PNG plots and
//                 results.json in DIR (see docs/validation/form-factors.md).
//   cie171        the analytical test cases of CIE 171:2006 section 5 that candela/1 expresses,
//                 probed by every method that answers them against references derived from their
//                 geometry (validate/cie171_validation.h); cie171.csv, summary.csv, results.json
//                 and a plot per case in DIR (see docs/validation/cie171.md). Exit status 1 when
//                 a method misses its tolerance somewhere (--methods a,b: only those methods).
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "commands.h"
#include "integrators/method_registry.h"
#include "integrators/probe.h"
#include "list_option.h"
#include "thread_limit.h"
#include "validate/cie171_validation.h"
#include "validate/form_factor_validation.h"
#include "validate/sphere_disc.h"

namespace candela::cli {

namespace {

struct ValidateOptions {
  std::string name;
  std::string out;
  bool quick = false;
  bool quiet = false;
  int threads = 0;
  std::vector<std::string> methods;
  std::vector<std::string> cases;
  std::vector<std::string> overrides;  // --set key=value (cie171's scenes)
};

int run_validate(const ValidateOptions& options) {
  if (options.name != "sphere-disc" && options.name != "form-factors" && options.name != "cie171")
    throw BadArgument(
        fmt::format("unknown validation case '{}' (known: sphere-disc, form-factors, cie171)", options.name));
  if (!options.methods.empty() && options.name != "cie171")
    throw BadArgument("--methods is for cie171 (sphere-disc and form-factors run their own methods)");
  for (const std::string& method : options.methods)
    if (const MethodEntry* entry = find_method(method); !entry || !entry->capabilities.probe)
      throw BadArgument(fmt::format("--methods: unknown method '{}' (expected {}: CIE 171 probes)", method,
                                    probe_method_names()));
  if (!options.cases.empty() && options.name != "cie171") throw BadArgument("--cases is for cie171");
  if (!options.overrides.empty() && options.name != "cie171")
    throw BadArgument("--set is for cie171 (sphere-disc and form-factors build their own scenes)");
  const std::vector<std::string> numbers = cie171_case_numbers();
  for (const std::string& number : options.cases)
    if (std::find(numbers.begin(), numbers.end(), number) == numbers.end())
      throw BadArgument(
          fmt::format("--cases: unknown case '{}' (expected one of {})", number, fmt::join(numbers, ", ")));
  if (options.name == "cie171") {
    Cie171Run settings_only;
    settings_only.overrides = options.overrides;
    check_cie171_overrides(settings_only);
  }
  std::optional<tbb::global_control> thread_limit;
  limit_threads(options.threads, thread_limit);
  namespace fs = std::filesystem;
  std::error_code error;
  fs::create_directories(options.out, error);
  if (error || !fs::is_directory(options.out))
    throw BadArgument(fmt::format("--out: cannot create the directory '{}'{}", options.out,
                                  error ? ": " + error.message() : ""));
  if (options.name == "cie171") {
    Cie171Run run;
    run.quick = options.quick;
    run.only_methods = options.methods;
    run.only_cases = options.cases;
    run.overrides = options.overrides;
    const nlohmann::json results =
        run_cie171_validation(options.out, run, options.quiet ? nullptr : &std::cout);
    const int failures = results["failures"].get<int>();
    if (!options.quiet)
      std::cout << fmt::format("{}; written to {}\n",
                               failures == 0 ? std::string("every method within its tolerance")
                                             : fmt::format("{} case-method pairs out of tolerance", failures),
                               options.out);
    return failures == 0 ? 0 : 1;
  }
  if (options.name == "form-factors") {
    FormFactorRun run;
    run.quick = options.quick;
    run_form_factor_validation(options.out, run, options.quiet ? nullptr : &std::cout);
    if (!options.quiet) std::cout << fmt::format("written to {}\n", options.out);
    return 0;
  }
  SphereDiscRun run;
  run.quick = options.quick;
  const nlohmann::json errors =
      run_sphere_disc_validation(options.out, run, options.quiet ? nullptr : &std::cout);
  if (!options.quiet)
    std::cout << fmt::format("least RMS error: {} (delta 3), {} (delta 1); written to {}\n",
                             errors["least_rms"]["delta3"].get<std::string>(),
                             errors["least_rms"]["delta1"].get<std::string>(), options.out);
  return 0;
}

}  // namespace

void add_validate_command(CLI::App& app, std::function<int()>& run) {
  auto options = std::make_shared<ValidateOptions>();
  CLI::App* command =
      app.add_subcommand("validate", "Run a built-in validation case (sphere-disc, form-factors, cie171)");
  command->add_option("name", options->name, "The case: sphere-disc, form-factors or cie171")->required();
  command->add_option("--out", options->out, "Directory for the CSV files, plots and errors.json")
      ->required();
  command->add_flag("--quick", options->quick, "Coarser reference and sampling (for tests)");
  command->add_flag("-q,--quiet", options->quiet, "No progress lines");
  add_list_option(command, "--methods", options->methods,
                  "cie171: only these methods (local, path, radiosity, meshless)");
  add_list_option(command, "--cases", options->cases,
                  "cie171: only these cases, by number (5.2, 5.3, 5.4, 5.5, 5.6, 5.7, 5.8, 5.9, 5.10, 5.11, "
                  "5.12, 5.13; 5.11: each of its variants)");
  // One key=value per --set, as for render.
  command
      ->add_option("--set", options->overrides,
                   "cie171: override a setting of every case's scene (KEY=VALUE, as for render), e.g. "
                   "another solver for a method")
      ->expected(1)
      ->allow_extra_args(false)
      ->take_all();
  command->add_option("--threads,--nthreads", options->threads, "Worker threads (default: all cores)");
  command->callback([options, &run]() {
    run = [options]() { return run_reporting_bad_input([&] { return run_validate(*options); }); };
  });
}

}  // namespace candela::cli
