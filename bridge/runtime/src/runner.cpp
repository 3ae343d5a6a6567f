// SPDX-License-Identifier: MIT
#include "hil/runtime/runner.hpp"

#include <csignal>
#include <optional>

#include <fmt/format.h>
#include <asio/io_context.hpp>
#include <asio/signal_set.hpp>

#include "hil/runtime/linux/absolute_sleeper.hpp"
#include "hil/runtime/linux/realtime_session.hpp"
#include "hil/runtime/program.hpp"
#include "hil/runtime/run_monitor.hpp"
#include "hil/runtime/scheduler.hpp"

namespace hil::runtime {
namespace {

constexpr Duration interrupt_grace = std::chrono::seconds(2);

bool at_rest(const Machine& m) {
  for (const auto& a : m.axes()) {
    const auto& st = a.axis->status();
    if (st.busy || st.state == motion::AxisState::moving || st.state == motion::AxisState::stopping ||
        st.state == motion::AxisState::homing || st.state == motion::AxisState::enabling)
      return false;
  }
  return true;
}

/// The per-cycle logic shared by both schedulers.
class Session {
 public:
  Session(const Scenario& s, Machine& m, const RunOptions& o)
      : scenario_(s), machine_(m), options_(o), program_(s, m), monitor_(s, m) {}

  std::optional<ConfigError> check() const { return program_.check(); }

  CycleControl cycle(const CycleTime& c) noexcept {
    if (!started_) {
      started_ = true;
      start_ = c.now;
    }
    const Duration t = c.now - start_;
    last_ = c;
    t_ = t;
    machine_.cycle(c);
    monitor_.observe(t);
    for (auto* o : options_.observers) o->on_cycle(t, machine_);
    if (interrupt_requested_ && !interrupted_) {
      interrupted_ = true;
      interrupted_at_ = t;
      for (auto& a : machine_.axes()) (void)a.axis->quick_stop();
    }
    if (interrupted_)
      return at_rest(machine_) || t - interrupted_at_ > interrupt_grace ? CycleControl::stop : CycleControl::proceed;
    const auto status = program_.step(t);
    if (status == Program::Status::failed) return CycleControl::stop;
    if (t >= scenario_.timeout) {
      timed_out_ = true;
      return CycleControl::stop;
    }
    if (scenario_.duration) {
      if (t + c.period < *scenario_.duration) return CycleControl::proceed;
      cut_ = describe_cut(status);
      return CycleControl::stop;
    }
    if (status != Program::Status::done || !at_rest(machine_)) {
      rest_since_.reset();
      return CycleControl::proceed;
    }
    if (!rest_since_) rest_since_ = t;
    // At rest; let standstill axes settle into their in-position window (bounded by the longest
    // in-position timeout, after which supervision would have faulted anyway).
    const bool settled = all_in_position(machine_) || t - *rest_since_ >= settle_limit();
    // The run also waits for the scenario's timed inputs and ends on a controller cycle, so
    // what the last cycles did (a fault, an input) has been through the device's own cycle.
    if (settled && t >= monitor_.latest_expectation_time() && t >= machine_.last_stimulus_time() &&
        machine_.controller_cycle_complete())
      return CycleControl::stop;
    return CycleControl::proceed;
  }

  void interrupt() noexcept { interrupt_requested_ = true; }

  /// At the last cycle of a fixed `duration:`: what the duration cut off (steps not completed,
  /// axes still in motion), or nothing when the program had ended and every axis was at rest.
  std::optional<std::string> describe_cut(Program::Status status) const {
    std::vector<std::string> what;
    if (status != Program::Status::done && program_.current_step() < scenario_.program.size()) {
      const std::size_t n = program_.current_step();
      const Step& st = scenario_.program[n];
      what.push_back(fmt::format("step {} of {} ({}, {}:{} {}) not completed", n + 1, scenario_.program.size(), st.name,
                                 scenario_.file, st.source.line, st.source.path));
    }
    for (const auto& a : machine_.axes()) {
      const auto& st = a.axis->status();
      if (st.busy || st.state == motion::AxisState::moving || st.state == motion::AxisState::stopping ||
          st.state == motion::AxisState::homing || st.state == motion::AxisState::enabling)
        what.push_back(fmt::format("axis {} still {}", a.spec->name,
                                   st.state == motion::AxisState::moving || st.state == motion::AxisState::standstill
                                       ? std::string("moving")
                                       : std::string(motion::to_string(st.state))));
    }
    if (what.empty()) return std::nullopt;
    std::string out = fmt::format("cut off by duration at t={:.3f} s: ", to_seconds(*scenario_.duration));
    for (std::size_t i = 0; i < what.size(); ++i) out += (i ? "; " : "") + what[i];
    return out;
  }

  static bool all_in_position(const Machine& m) {
    for (const auto& a : m.axes()) {
      const auto& st = a.axis->status();
      if (st.state == motion::AxisState::standstill && !st.in_position) return false;
    }
    return true;
  }
  Duration settle_limit() const {
    Duration d{};
    for (const auto& a : machine_.axes()) d = std::max(d, a.axis->config().in_position_timeout);
    return d + scenario_.period;
  }

  RunResult finish(const SchedulerStats& stats) {
    RunResult r;
    r.scenario = scenario_.name.empty() ? scenario_.file : scenario_.name;
    r.file = scenario_.file;
    r.scheduler = stats;
    r.simulated = t_;
    r.interrupted = interrupted_;
    if (program_.status() == Program::Status::failed) {
      r.ok = false;
      r.failures.push_back("program failed: " + program_.error());
    }
    if (timed_out_) {
      r.ok = false;
      r.failures.push_back(fmt::format(
          "timeout: the scenario ran {:.3f} s (timeout {:.3f} s) and was still at step {} "
          "of {}",
          to_seconds(t_), to_seconds(scenario_.timeout), program_.current_step() + 1, scenario_.program.size()));
    }
    if (cut_) {
      r.cut_off = *cut_;
      r.cut_off_expected = scenario_.cut_off_expected;
      if (!scenario_.cut_off_expected) {
        r.ok = false;
        r.failures.push_back(*cut_ + " (say `cut_off: expected` in the scenario when the cut is intended)");
      }
    }
    if (interrupted_) {
      r.ok = false;
      r.failures.push_back(fmt::format("interrupted at t={:.3f} s", to_seconds(interrupted_at_)));
    }
    monitor_.finish(t_, r);
    r.reports = machine_.finish(last_);
    for (const auto& rep : r.reports) {
      if (rep.report.ok) continue;
      r.ok = false;
      r.failures.push_back(fmt::format("transport {} reported a failure{}", rep.transport,
                                       rep.report.lines.empty() ? "" : ": " + rep.report.lines.front()));
    }
    for (auto* o : options_.observers) o->on_finish(r);
    return r;
  }

 private:
  const Scenario& scenario_;
  Machine& machine_;
  const RunOptions& options_;
  Program program_;
  RunMonitor monitor_;
  bool started_ = false;
  TimePoint start_{};
  CycleTime last_{};
  Duration t_{};
  bool timed_out_ = false;
  bool interrupt_requested_ = false;
  bool interrupted_ = false;
  Duration interrupted_at_{};
  std::optional<Duration> rest_since_;
  std::optional<std::string> cut_;  ///< set at the cycle the fixed duration ended the run
};

}  // namespace

std::expected<RunResult, ConfigError> run_scenario(const Scenario& scenario, const TransportRegistry& registry,
                                                   const RunOptions& options) {
  if (options.virtual_time) {
    VirtualClock clock;
    RunEnvironment env{clock, true, nullptr, scenario.file, scenario.period, options.verify_steps, {}};
    auto machine = Machine::build(scenario, registry, env, options.controllers);
    if (!machine) return std::unexpected(machine.error());
    Session session(scenario, *machine, options);
    if (auto e = session.check()) return std::unexpected(*e);
    for (auto* o : options.observers) o->on_start(scenario, *machine);
    VirtualScheduler scheduler(clock, scenario.period);
    const auto stats = scheduler.run([&](const CycleTime& c) { return session.cycle(c); });
    return session.finish(stats);
  }
  // Real time: settle the cycle thread's environment before the transports start their threads
  // (they inherit the CPUs other than the cycle CPU), then move this thread onto its CPU.
  std::unique_ptr<linux_rt::RealtimeSession> realtime;
  if (options.realtime.enabled) {
    auto rt = linux_rt::RealtimeSession::begin(options.realtime);
    if (!rt) return std::unexpected(ConfigError{"", 0, 0, "realtime", rt.error().message});
    realtime = std::move(*rt);
  }
  asio::io_context io;
  SteadyClock clock;
  RunEnvironment env{clock, false, &io, scenario.file, scenario.period, options.verify_steps, {}};
  auto machine = Machine::build(scenario, registry, env, options.controllers);
  if (!machine) return std::unexpected(machine.error());
  Session session(scenario, *machine, options);
  if (auto e = session.check()) return std::unexpected(*e);
  std::optional<linux_rt::AbsoluteSleeper> sleeper;
  if (realtime) {
    realtime->enter_cycle_cpu();
    sleeper.emplace(clock);
  }
  for (auto* o : options.observers) o->on_start(scenario, *machine);
  AsioScheduler scheduler(io, clock, scenario.period, sleeper ? &*sleeper : nullptr);
  std::optional<asio::signal_set> signals;
  if (options.handle_signals) {
    signals.emplace(io, SIGINT, SIGTERM);
    signals->async_wait([&](const std::error_code& ec, int) {
      if (!ec) session.interrupt();
    });
  }
  SchedulerStats stats;
  scheduler.async_run([&](const CycleTime& c) { return session.cycle(c); },
                      [&](const SchedulerStats& s) {
                        stats = s;
                        if (signals) signals->cancel();
                      });
  // Transports may keep work (pending socket reads) on the context: run only until the scheduler
  // is done, let the factories finish, then flush what is ready.
  scheduler.run_until_done();
  RunResult r = session.finish(stats);
  if (realtime) r.realtime = realtime->report();
  io.poll();
  return r;
}

}  // namespace hil::runtime
