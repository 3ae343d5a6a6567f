// SPDX-License-Identifier: MIT
// `hilbridge latency`: a machine check like cyclictest or LinuxCNC's latency test. Runs the cycle
// scheduler's own wake-up loop (an empty cycle) for N seconds at a period, on normal scheduling
// (the Asio timer, as `hilbridge run`) or with --realtime (SCHED_FIFO, memory lock, own CPU,
// cpu_dma_latency 0, clock_nanosleep wake-ups, as `hilbridge run --realtime`), optionally under
// a CPU and memory load, and prints the latency histogram and the minimum cycle period it
// recommends for this machine.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <csignal>
#include <cstring>
#include <optional>
#include <thread>
#include <vector>

#include <fmt/format.h>
#include <asio/io_context.hpp>
#include <asio/signal_set.hpp>

#include "hil/cli/context.hpp"
#include "hil/cli/duration_option.hpp"
#include "hil/runtime/latency_report.hpp"
#include "hil/runtime/linux/absolute_sleeper.hpp"
#include "hil/runtime/linux/realtime_session.hpp"
#include "hil/runtime/scenario_loader.hpp"
#include "hil/runtime/scheduler.hpp"
#include "run_json.hpp"

namespace hil::cli {
namespace {

struct LatencyArgs {
  Duration duration = std::chrono::seconds(10);
  Duration period = std::chrono::milliseconds(1);
  int realtime_priority = 0;
  int realtime_cpu = -1;
  bool realtime_fallback = false;
  bool load = false;
  bool json = false;
};

/// One busy thread per CPU: copies 4 MiB blocks (caches and memory bus) and yields now and then
/// (scheduler traffic), until stopped. Started before the real-time settings, so every CPU,
/// the cycle CPU included, gets its share.
class LoadGenerator {
 public:
  explicit LoadGenerator(unsigned threads) {
    for (unsigned i = 0; i < threads; ++i)
      threads_.emplace_back([this] {
        std::vector<char> a(4 << 20, 1), b(4 << 20, 2);
        unsigned n = 0;
        while (!stop_.load(std::memory_order_relaxed)) {
          std::memcpy(b.data(), a.data(), a.size());
          std::swap(a, b);
          if (++n % 8 == 0) std::this_thread::yield();
        }
      });
  }
  ~LoadGenerator() {
    stop_ = true;
    for (auto& t : threads_) t.join();
  }
  LoadGenerator(const LoadGenerator&) = delete;
  LoadGenerator& operator=(const LoadGenerator&) = delete;

 private:
  std::atomic<bool> stop_{false};
  std::vector<std::thread> threads_;
};

std::string period_text(Duration d) {
  return d >= std::chrono::milliseconds(1) ? fmt::format("{:g} ms", to_microseconds(d) / 1000.0)
                                           : fmt::format("{:g} us", to_microseconds(d));
}

int latency_command(const LatencyArgs& args) {
  const double seconds = to_seconds(args.duration);
  const Duration period = args.period;  // checked by its option: 50us .. 1s
  const auto cycles = static_cast<std::uint64_t>(std::max(1.0, std::round(seconds / to_seconds(period))));

  std::optional<LoadGenerator> load;
  if (args.load) load.emplace(std::max(1u, std::thread::hardware_concurrency()));

  std::unique_ptr<runtime::linux_rt::RealtimeSession> realtime;
  if (args.realtime_priority > 0) {
    runtime::RealtimeOptions o;
    o.enabled = true;
    o.priority = args.realtime_priority;
    if (args.realtime_cpu >= 0) o.cpu = args.realtime_cpu;
    o.fallback = args.realtime_fallback;
    auto rt = runtime::linux_rt::RealtimeSession::begin(o);
    if (!rt) {
      fmt::print(stderr,
                 "error: realtime: {}\nRun without --realtime to measure normal scheduling, or add "
                 "--realtime-fallback.\n",
                 rt.error().message);
      return 2;
    }
    realtime = std::move(*rt);
    realtime->enter_cycle_cpu();
  }

  asio::io_context io;
  SteadyClock clock;
  std::optional<runtime::linux_rt::AbsoluteSleeper> sleeper;
  if (realtime) sleeper.emplace(clock);
  runtime::AsioScheduler scheduler(io, clock, period, sleeper ? &*sleeper : nullptr);
  asio::signal_set signals(io, SIGINT, SIGTERM);
  bool interrupted = false;
  signals.async_wait([&](const std::error_code& ec, int) {
    if (ec) return;
    interrupted = true;
    scheduler.stop();
  });
  if (!args.json)
    fmt::print("measuring wake-up latency for {:g} s at {} ({}{}), Ctrl-C ends early...\n", seconds,
               period_text(period), realtime ? realtime->report().describe() : "normal scheduling, Asio timer",
               load ? ", under load" : "");
  std::fflush(stdout);
  runtime::SchedulerStats stats;
  scheduler.async_run([](const CycleTime&) { return runtime::CycleControl::proceed; },
                      [&](const runtime::SchedulerStats& s) {
                        stats = s;
                        signals.cancel();
                      },
                      cycles);
  scheduler.run_until_done();
  io.poll();
  const runtime::RealtimeReport report = realtime ? realtime->report() : runtime::RealtimeReport{};
  realtime.reset();
  load.reset();

  const auto& h = stats.wake_latency;
  const auto recommended = runtime::recommended_min_period(h, stats.max_cycle_work);
  if (args.json) {
    fmt::print(
        "{{\"seconds\":{:.6f},\"period_us\":{:.3f},\"realtime\":{},\"load\":{},\"interrupted\":{},\"cycles\":{},"
        "\"overruns\":{},\"skipped_cycles\":{},\"max_cycle_work_us\":{:.3f},\"wake_latency\":{},"
        "\"recommended_min_period_us\":{}}}\n",
        to_seconds(stats.wall), to_microseconds(period), report.requested ? realtime_json(report) : "null", args.load,
        interrupted, stats.cycles, stats.overruns, stats.skipped_cycles, to_microseconds(stats.max_cycle_work),
        runtime::latency_json(h), recommended ? fmt::format("{:.0f}", to_microseconds(*recommended)) : "null");
    return 0;
  }
  fmt::print("{} wake-ups in {:.3f} s{}\n", stats.cycles, to_seconds(stats.wall), interrupted ? " (interrupted)" : "");
  fmt::print("wake-up latency: min {:.0f} us, mean {:.1f} us, p99 {:.0f} us, p99.9 {:.0f} us, max {:.0f} us\n",
             to_microseconds(h.min()), to_microseconds(h.mean()), to_microseconds(h.percentile(0.99)),
             to_microseconds(h.percentile(0.999)), to_microseconds(h.max()));
  fmt::print("{}", runtime::format_latency_histogram(h, "  "));
  fmt::print("overruns: {}, skipped cycles: {}\n", stats.overruns, stats.skipped_cycles);
  if (recommended)
    fmt::print(
        "recommended minimum cycle period: {} (at least twice the worst wake-up latency of {:.0f} us, so a cycle "
        "woken at its worst still has half its period for its work){}\n",
        period_text(*recommended), to_microseconds(h.max()),
        report.priority > 0 ? "" : "; try --realtime for a better figure");
  else
    fmt::print("recommended minimum cycle period: none up to 1 s (worst wake-up latency {:.0f} us)\n",
               to_microseconds(h.max()));
  return 0;
}

}  // namespace

void register_latency_command(Context& ctx) {
  auto args = std::make_shared<LatencyArgs>();
  auto* cmd = ctx.app.add_subcommand("latency", "Measure this machine's cycle wake-up latency (like cyclictest)");
  cmd->footer(
      "Runs the cycle scheduler's own wake-up loop with an empty cycle for --duration at --period and prints\n"
      "the wake-up latency (actual wake-up minus deadline: min, mean, p99, p99.9, max and a histogram),\n"
      "overruns and skipped cycles, and the smallest standard cycle period at least twice the worst latency.\n"
      "Without --realtime it measures what `hilbridge run` gets on normal scheduling (Asio timer); with\n"
      "--realtime what `hilbridge run --realtime` gets. --load adds one CPU and memory hog per CPU.\n"
      "Run it before choosing a scenario's period: docs/runtime.md. Exit status: 0 measured; 2 bad option or\n"
      "a real-time setting refused (the message says what to do).");
  const DurationRange duration_range{std::chrono::microseconds(1), std::chrono::hours(24)};
  add_duration_option(*cmd, "--duration", args->duration, "How long to measure, e.g. 60s (default 10s; at most 24h)",
                      "s", duration_range);
  add_duration_alias(*cmd, "--seconds", "--duration", args->duration, "s", duration_range);
  add_duration_option(*cmd, "--period", args->period, "Cycle period to wake up at (default 1ms; 50us .. 1s)", "s",
                      {std::chrono::microseconds(50), std::chrono::seconds(1)});
  cmd->add_flag("--realtime{80}", args->realtime_priority,
                "Measure with the real-time settings of `hilbridge run --realtime` at SCHED_FIFO PRIO (default 80)")
      ->check(CLI::Range(1, 99));
  cmd->add_option("--realtime-cpu", args->realtime_cpu, "CPU for the measuring thread (default as hilbridge run)")
      ->check(CLI::Range(0, 1023));
  cmd->add_flag("--realtime-fallback", args->realtime_fallback,
                "When a real-time setting is refused, report it and measure without it");
  cmd->add_flag("--load", args->load, "Run a CPU and memory load on every CPU while measuring");
  cmd->add_flag("--json", args->json, "Print the result as one JSON document");
  cmd->callback([&ctx, args] { ctx.exit_code = latency_command(*args); });
}

}  // namespace hil::cli
