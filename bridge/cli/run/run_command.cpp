// SPDX-License-Identifier: MIT
// CLI module `run`: `hilbridge run [scenario.yaml]` (and `hilbridge test`, test_command.cpp).
#include <fmt/format.h>

#include "examples.hpp"
#include "hil/cli/context.hpp"
#include "hil/runtime/runner.hpp"
#include "hil/runtime/scenario_loader.hpp"
#include "live_status.hpp"
#include "report.hpp"
#include "run_outputs.hpp"

namespace hil::cli {

void register_test_command(Context& ctx);

namespace {

struct RunArgs {
  std::string scenario;
  bool virtual_time = false;
  bool verify_steps = false;
  bool quiet = false;
  std::string trace;
  std::string plot;
};

int run_command(Context& ctx, const RunArgs& args) {
  std::filesystem::path file = args.scenario;
  if (file.empty()) {
    auto demo = find_example("demo.yaml");
    if (!demo) {
      std::string where;
      for (const auto& d : example_dirs()) where += "\n  " + d.string();
      fmt::print(stderr,
                 "error: no scenario given and the bundled demo examples/demo.yaml was not found; looked in:{}\n"
                 "Give a scenario file (hilbridge run FILE.yaml) or set HILBRIDGE_EXAMPLES to the examples folder.\n",
                 where);
      return 2;
    }
    file = *demo;
  }
  auto scenario = runtime::load_scenario(file);
  if (!scenario) {
    fmt::print(stderr, "error: {}\n", scenario.error().describe());
    return 2;
  }
  LiveStatus live(stdout);
  RunOutputs outputs;
  if (auto e = outputs.open(args.trace, args.plot)) {
    fmt::print(stderr, "error: {}\n", *e);
    return 2;
  }
  runtime::RunOptions options;
  options.virtual_time = args.virtual_time;
  options.verify_steps = args.verify_steps;
  options.handle_signals = true;
  if (!args.quiet) options.observers.push_back(&live);
  for (auto* o : outputs.observers()) options.observers.push_back(o);
  auto result = runtime::run_scenario(*scenario, ctx.transports, options);
  if (!result) {
    fmt::print(stderr, "error: {}\n", result.error().describe());
    return 2;
  }
  print_summary(stdout, *result);
  bool ok = result->ok;
  if (auto e = outputs.close(*result)) {
    fmt::print(stderr, "error: {}\n", *e);
    ok = false;
  }
  for (const auto& f : outputs.written()) fmt::print("wrote {}\n", f);
  return ok ? 0 : 1;
}

}  // namespace

void register_run(Context& ctx) {
  auto args = std::make_shared<RunArgs>();
  // One line for `hilbridge --help`; the details go to the footer of `hilbridge run --help`.
  auto* run =
      ctx.app.add_subcommand("run", "Run a motion scenario on real time or --virtual (no file: the bundled demo)");
  run->footer(
      "Run a motion scenario (YAML: machine + program + expectations) on real time, or as fast as\n"
      "possible with --virtual. With no file, runs the bundled demo examples/demo.yaml (three axes on\n"
      "simulated drives). Shows a live status line per axis and ends with a summary: final positions,\n"
      "maximum following errors, faults, scheduler jitter and overruns, and every transport's report.\n"
      "Exit status: 0 ok; 1 a fault, a failed expectation or step, a failed transport report;\n"
      "2 the scenario or an option is invalid.\n"
      "Scenario keys: docs/scenarios.md. The demo is searched in $HILBRIDGE_EXAMPLES, <exe>/../examples,\n"
      "<exe>/examples and ./examples.");
  // No CLI::ExistingFile check: the loader reports a missing file as file: error with exit status 2.
  run->add_option("scenario", args->scenario, "Scenario file (default: the bundled examples/demo.yaml)");
  run->add_flag("--virtual", args->virtual_time,
                "Run on virtual time as fast as the CPU allows (same cycle code; no real-time I/O)");
  run->add_option("--trace", args->trace,
                  "Write per-cycle data per axis to this CSV file (t, position, command, velocity, following "
                  "error, state, fault)");
  run->add_option("--plot", args->plot,
                  "Draw position, velocity and following error over time per axis into this SVG file");
  run->add_flag("--verify-steps", args->verify_steps,
                "Ask step/direction transports to verify their edge streams (timing rules); a violation fails "
                "the run");
  run->add_flag("-q,--quiet", args->quiet, "No live status, only the summary");
  run->callback([&ctx, args] { ctx.exit_code = run_command(ctx, *args); });
  register_test_command(ctx);
}

}  // namespace hil::cli
