// SPDX-License-Identifier: MIT
// CLI module `run`: `hilbridge run [scenario.yaml]` (and `hilbridge test`, test_command.cpp).
#include <algorithm>

#include <fmt/format.h>

#include "examples.hpp"
#include "hil/cli/context.hpp"
#include "hil/cli/duration_option.hpp"
#include "hil/cli/json_output.hpp"
#include "hil/runtime/runner.hpp"
#include "hil/runtime/scenario_loader.hpp"
#include "live_status.hpp"
#include "report.hpp"
#include "run_json.hpp"
#include "run_outputs.hpp"

namespace hil::cli {

void register_test_command(Context& ctx);
void register_latency_command(Context& ctx);

namespace {

struct RunArgs {
  std::string scenario;
  bool virtual_time = false;
  bool verify_steps = false;
  bool quiet = false;
  bool json = false;
  std::string trace;
  std::string plot;
  Duration duration{};        ///< 0: the scenario's own duration:
  int realtime_priority = 0;  ///< --realtime[=PRIO]; 0 = not given
  int realtime_cpu = -1;      ///< --realtime-cpu; -1 = not given
  bool realtime_fallback = false;
  bool no_realtime = false;
};

// The scenario's `realtime:` key, then the command line on top of it.
runtime::RealtimeOptions realtime_options(const runtime::Scenario& s, const RunArgs& args) {
  runtime::RealtimeOptions o = s.realtime.value_or(runtime::RealtimeOptions{});
  if (args.realtime_priority > 0) {
    o.enabled = true;
    o.priority = args.realtime_priority;
  }
  if (args.realtime_cpu >= 0) o.cpu = args.realtime_cpu;
  if (args.realtime_fallback) o.fallback = true;
  if (args.no_realtime) o.enabled = false;
  return o;
}

int run_command(Context& ctx, const RunArgs& args) {
  const auto failed = [&](const std::string& what) { return report_error(args.json, "error: ", what, 2); };
  std::filesystem::path file = args.scenario;
  if (file.empty()) {
    auto demo = find_example("demo.yaml");
    if (!demo) {
      std::string where;
      for (const auto& d : example_dirs()) where += "\n  " + d.string();
      return failed(fmt::format(
          "no scenario given and the bundled demo examples/demo.yaml was not found; looked in:{}\n"
          "Give a scenario file (hilbridge run FILE.yaml) or set HILBRIDGE_EXAMPLES to the examples folder.",
          where));
    }
    file = *demo;
  }
  auto scenario = runtime::load_scenario(file);
  if (!scenario) return failed(scenario.error().describe());
  if (args.duration > Duration::zero()) {
    scenario->duration = args.duration;
    scenario->timeout = std::max(scenario->timeout, args.duration);
    // "Run this long, whatever the program does": a cut by --duration is what was asked for.
    scenario->cut_off_expected = true;
  }
  const runtime::RealtimeOptions realtime = realtime_options(*scenario, args);
  if (realtime.enabled && args.virtual_time && args.realtime_priority > 0)
    return failed("--realtime and --virtual exclude each other (virtual time never waits)");
  LiveStatus live(args.json ? stderr : stdout);
  RunOutputs outputs;
  if (auto e = outputs.open(args.trace, args.plot)) return failed(*e);
  runtime::RunOptions options;
  options.virtual_time = args.virtual_time;
  options.verify_steps = args.verify_steps;
  options.handle_signals = true;
  options.realtime = realtime;
  if (args.virtual_time) options.realtime.enabled = false;
  if (!args.quiet) options.observers.push_back(&live);
  for (auto* o : outputs.observers()) options.observers.push_back(o);
  auto result = runtime::run_scenario(*scenario, ctx.transports, options);
  if (!result) {
    if (result.error().key == "realtime")
      return failed(result.error().describe() +
                    "\nRun without --realtime, or add --realtime-fallback to run on normal scheduling.");
    return failed(result.error().describe());
  }
  if (args.json)
    fmt::print(stdout, "{}", run_json(*result));
  else
    print_summary(stdout, *result);
  bool ok = result->ok;
  if (auto e = outputs.close(*result)) {
    fmt::print(stderr, "error: {}\n", *e);
    ok = false;
  }
  for (const auto& f : outputs.written()) fmt::print(args.json ? stderr : stdout, "wrote {}\n", f);
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
  run->add_flag("--json", args->json,
                "Print the result as JSON on stdout instead of the summary (scheduler statistics with the "
                "wake-up latency histogram, real-time settings); the live status goes to stderr");
  add_duration_option(*run, "--duration", args->duration,
                      "Run this long (e.g. 60s), whatever the program does; overrides the scenario's duration:", "s",
                      {std::chrono::microseconds(1)});
  run->add_flag("--realtime{80}", args->realtime_priority,
                "Run the cycle thread on real time: SCHED_FIFO at PRIO (default 80; --realtime=90), memory "
                "locked, pinned to its own CPU, /dev/cpu_dma_latency held at 0, clock_nanosleep wake-ups. "
                "Needs root or CAP_SYS_NICE + CAP_IPC_LOCK (docs/runtime.md); fails with what to do otherwise")
      ->check(CLI::Range(1, 99));
  run->add_option("--realtime-cpu", args->realtime_cpu,
                  "CPU for the cycle thread (default: the first isolated CPU, else the last one); other threads "
                  "keep off it")
      ->check(CLI::Range(0, 1023));
  run->add_flag("--realtime-fallback", args->realtime_fallback,
                "When a real-time setting is refused, report it and run without it instead of failing");
  run->add_flag("--no-realtime", args->no_realtime, "Ignore the scenario's realtime: key (normal scheduling)");
  run->callback([&ctx, args] { ctx.exit_code = run_command(ctx, *args); });
  register_test_command(ctx);
  register_latency_command(ctx);
}

}  // namespace hil::cli
