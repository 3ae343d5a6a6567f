// SPDX-License-Identifier: MIT
// CLI module `stepdir`: registers the stepdir transport for `hilbridge run`, and
//   hilbridge stepdir plan    print (and verify) the edge schedule of one IP247 move
//   hilbridge stepdir verify  check a recorded edge log against the timing rules
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>

#include <fmt/format.h>

#include "hil/cli/context.hpp"
#include "hil/cli/duration_option.hpp"
#include "hil/drives/stepdir/transport_factory.hpp"
#include "hil/stepdir/edge_log.hpp"
#include "hil/stepdir/ip247_ramp.hpp"
#include "hil/stepdir/step_planner.hpp"
#include "hil/stepdir/verifier.hpp"

namespace hil::cli {
namespace {

using namespace hil::stepdir;

struct TimingOptions {
  double fmax = 5'000, fss = 200, accel = 50'000;
  Duration pulse = std::chrono::microseconds(2);
  std::string rounding = "up", polarity = "positive";
  Duration dir_setup = std::chrono::microseconds(5), dir_hold = std::chrono::microseconds(5);

  void add(CLI::App& app) {
    app.add_option("--fmax", fmax, "Maximum step frequency f_max in Hz (12..100000; IP247 MD n+5)")
        ->capture_default_str();
    app.add_option("--fss", fss, "Start-stop frequency f_ss in Hz (1..10000; MD n+7)")->capture_default_str();
    app.add_option("--accel", accel, "Frequency increase a in Hz/s (= mHz/ms; MD n+9)")->capture_default_str();
    // Durations with units (docs/cli.md); the old unit-in-the-name options are hidden aliases that warn.
    const DurationRange up_to_1s{Duration{}, std::chrono::seconds(1)};
    add_duration_option(app, "--pulse", pulse,
                        "Step pulse duration, whole microseconds 1us..31us (IP247 MD; output in 2 us steps)", "us",
                        up_to_1s)
        ->default_str(format_duration(pulse));
    add_duration_alias(app, "--pulse-us", "--pulse", pulse, "us", up_to_1s);
    app.add_option("--rounding", rounding, "Pulse quantisation: up or down")
        ->check(CLI::IsMember({"up", "down"}))
        ->capture_default_str();
    app.add_option("--polarity", polarity, "Active step edge: positive (idle low) or negative (idle high)")
        ->check(CLI::IsMember({"positive", "negative"}))
        ->capture_default_str();
    add_duration_option(app, "--dir-setup", dir_setup, "Direction setup before the active edge (0 .. 1s, e.g. 200ns)",
                        "ns", up_to_1s)
        ->default_str(format_duration(dir_setup));
    add_duration_alias(app, "--dir-setup-ns", "--dir-setup", dir_setup, "ns", up_to_1s);
    add_duration_option(app, "--dir-hold", dir_hold, "Direction hold after the trailing edge (0 .. 1s, e.g. 5us)", "ns",
                        up_to_1s)
        ->default_str(format_duration(dir_hold));
    add_duration_alias(app, "--dir-hold-ns", "--dir-hold", dir_hold, "ns", up_to_1s);
  }
  /// Timing + ramp, or an error message naming the MD error.
  std::expected<std::pair<StepTiming, Ip247Ramp>, std::string> build() const {
    // The IP247 machine data set the pulse in whole microseconds.
    if (pulse % std::chrono::microseconds(1) != Duration{})
      return std::unexpected(fmt::format("--pulse {}: the IP247 step pulse is set in whole microseconds (1us .. 31us)",
                                         format_duration(pulse)));
    const auto ns = [](Duration d) { return std::chrono::duration_cast<std::chrono::nanoseconds>(d).count(); };
    auto t = make_ip247_timing(static_cast<int>(pulse / std::chrono::microseconds(1)),
                               rounding == "up" ? PulseRounding::up : PulseRounding::down, fmax,
                               polarity == "positive" ? Polarity::positive_edge : Polarity::negative_edge,
                               ns(dir_setup), ns(dir_hold));
    if (!t) {
      return std::unexpected(
          fmt::format("IP247 MD error {}: {}", static_cast<int>(t.error()), make_error_code(t.error()).message()));
    }
    auto r = Ip247Ramp::make({fmax, fss, accel}, t->min_period_ns());
    if (!r) {
      return std::unexpected(
          fmt::format("IP247 MD error {}: {}", static_cast<int>(r.error()), make_error_code(r.error()).message()));
    }
    return std::pair{*t, std::move(*r)};
  }
};

void print_stats(const VerifyStats& st, std::FILE* out) {
  fmt::print(out, "steps: {} forward, {} backward (net {:+}); first interval {:.3f} us; fastest {:.1f} Hz\n",
             st.steps_forward, st.steps_backward, st.net_steps(), static_cast<double>(st.first_interval_ns) / 1000.0,
             st.max_frequency_hz());
}

}  // namespace

void register_stepdir(Context& ctx) {
  ctx.transports.add("stepdir", [] { return std::make_unique<hil::drives::stepdir::StepDirTransportFactory>(); });

  auto* sd = ctx.app.add_subcommand(
      "stepdir",
      "GPIO step/direction tools: plan an IP247 move into a timestamped edge schedule, verify an edge log.\n"
      "Axes on step/dir run with `hilbridge run` (drive: {transport: stepdir, ...}); see docs/stepdir.md.");
  sd->require_subcommand(1);

  // plan
  auto opts = std::make_shared<TimingOptions>();
  auto* plan = sd->add_subcommand(
      "plan",
      "Plan one move with the IP247 profile (jump to f_ss, exponential acceleration f = F(1-e^(-t/tau)) + f_ss,\n"
      "mirrored deceleration) and print its edges as '<time_ns> <line> <level>' lines, or a summary.\n"
      "Example: hilbridge stepdir plan --distance 2000 --fmax 5000 --fss 200 --accel 50000 --pulse 30us --summary");
  opts->add(*plan);
  auto distance = std::make_shared<std::int64_t>(0);
  auto speed = std::make_shared<double>(0.0);
  auto backlash = std::make_shared<std::int64_t>(0);
  auto output = std::make_shared<std::string>();
  auto summary = std::make_shared<bool>(false);
  auto verify = std::make_shared<bool>(false);
  // IP247 distances are signed 32-bit (manual digest); INT64_MIN/MAX made the planner hang.
  plan->add_option("--distance", *distance, "Distance in steps (negative = backward)")
      ->required()
      ->check(CLI::Range(std::int64_t{-2147483647}, std::int64_t{2147483647}));
  plan->add_option("--speed", *speed, "Commanded frequency f_v in Hz (default f_max; clamped to f_ss..f_max)");
  plan->add_option("--backlash", *backlash, "Backlash steps; the move is planned after a reversal so they are added")
      ->check(CLI::Range(std::int64_t{0}, std::int64_t{2147483647}));
  plan->add_option("-o,--output", *output, "Write the edge log to this file instead of stdout");
  plan->add_flag("--summary", *summary, "Print only the summary (steps, duration, frequencies), no edges");
  plan->add_flag("--verify", *verify, "Check the schedule with the verifier; exit 1 on the first violation");
  plan->callback([&ctx, opts, distance, speed, backlash, output, summary, verify] {
    auto built = opts->build();
    if (!built) {
      fmt::print(stderr, "hilbridge stepdir plan: {}\n", built.error());
      ctx.exit_code = 2;
      return;
    }
    auto& [timing, ramp] = *built;
    const double f_v = *speed > 0 ? *speed : opts->fmax;
    auto shared = std::make_shared<const Ip247Ramp>(std::move(ramp));
    StepPlanner p(timing, shared, *backlash);
    std::vector<gpio::Edge> edges;
    if (*backlash > 0) {
      // Establish the previous direction so this move is a reversal.
      p.set_position(0, *distance >= 0 ? -1 : 1);
    }
    if (!p.move_to(*distance, f_v)) {
      fmt::print(stderr, "note: IP247 warning 7: f_v {} Hz clamped to {}..{} Hz\n", f_v, opts->fss, opts->fmax);
    }
    p.plan(0, plan_forever_ns, edges);
    VerifyStats st;
    auto v = verify_edges(edges, timing, p.motor_position(), {}, &st);
    if (!*summary) {
      const std::string text = format_edge_log(edges);
      if (output->empty()) {
        std::fwrite(text.data(), 1, text.size(), stdout);
      } else {
        std::ofstream f(*output, std::ios::binary);
        f.write(text.data(), static_cast<std::streamsize>(text.size()));
        if (!f) {
          fmt::print(stderr, "hilbridge stepdir plan: cannot write '{}'\n", *output);
          ctx.exit_code = 2;
          return;
        }
      }
    }
    std::FILE* info = *summary ? stdout : stderr;
    fmt::print(info,
               "move: {} steps + {} backlash at up to {:.1f} Hz; F = {:.3f} Hz, tau = {:.3f} ms; duration {:.3f} ms\n",
               *distance, p.backlash_steps_total(), f_v, shared->big_f_hz(), shared->tau_s() * 1e3,
               edges.empty() ? 0.0 : static_cast<double>(edges.back().t_ns) * 1e-6);
    print_stats(st, info);
    if (*verify) {
      if (v) {
        fmt::print(info, "verify: FAILED: {}\n", v->describe());
        ctx.exit_code = 1;
      } else {
        fmt::print(info, "verify: ok (widths, spaces, dir setup/hold, f_max, step count)\n");
      }
    }
  });

  // verify
  auto vopts = std::make_shared<TimingOptions>();
  auto* ver = sd->add_subcommand(
      "verify",
      "Check an edge log ('<time_ns> step|dir|enable|<index> 0|1' per line, '#' comments) against the timing\n"
      "rules: pulse width, space, f_max, direction setup/hold, no dir change during a pulse, step count.\n"
      "Exit status: 0 ok, 1 violation (the first one is printed), 2 unreadable or malformed log.");
  vopts->add(*ver);
  auto file = std::make_shared<std::string>();
  auto expect = std::make_shared<std::int64_t>(0);
  auto expect_set = std::make_shared<CLI::Option*>(nullptr);
  ver->add_option("file", *file, "Edge log ('-' = stdin)")->required();
  *expect_set = ver->add_option("--expect-steps", *expect, "Expected net step count (forward minus backward)");
  ver->callback([&ctx, vopts, file, expect, expect_set] {
    auto built = vopts->build();
    if (!built) {
      fmt::print(stderr, "hilbridge stepdir verify: {}\n", built.error());
      ctx.exit_code = 2;
      return;
    }
    std::stringstream buf;
    if (*file == "-") {
      buf << std::cin.rdbuf();
    } else {
      std::ifstream f(*file, std::ios::binary);
      if (!f) {
        fmt::print(stderr, "hilbridge stepdir verify: cannot open '{}'\n", *file);
        ctx.exit_code = 2;
        return;
      }
      buf << f.rdbuf();
    }
    auto edges = parse_edge_log(buf.str());
    if (!edges) {
      fmt::print(stderr, "{}:{}\n", *file, edges.error().describe());
      ctx.exit_code = 2;
      return;
    }
    VerifyStats st;
    std::optional<std::int64_t> want;
    if ((*expect_set)->count()) want = *expect;
    auto v = verify_edges(*edges, built->first, want, {}, &st);
    print_stats(st, stdout);
    if (v) {
      fmt::print("{}: FAILED: {}\n", *file, v->describe());
      ctx.exit_code = 1;
    } else {
      fmt::print("{}: ok, {} edges\n", *file, edges->size());
    }
  });
}

}  // namespace hil::cli
