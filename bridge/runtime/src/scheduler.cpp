// SPDX-License-Identifier: MIT
#include "hil/runtime/scheduler.hpp"

#include <asio/executor_work_guard.hpp>
#include <asio/io_context.hpp>
#include <asio/steady_timer.hpp>

namespace hil::runtime {

VirtualScheduler::VirtualScheduler(VirtualClock& clock, Duration period) noexcept
    : clock_(clock), period_(period > Duration::zero() ? period : std::chrono::milliseconds(1)) {}

SchedulerStats VirtualScheduler::run(const CycleFunction& fn, std::uint64_t max_cycles) {
  SchedulerStats s;
  s.virtual_time = true;
  s.period = period_;
  const auto wall_start = std::chrono::steady_clock::now();
  const TimePoint start = clock_.now();
  CycleTime cycle{start, period_};
  while (s.cycles < max_cycles) {
    cycle.now = clock_.now();
    ++s.cycles;
    const CycleControl c = fn(cycle);
    if (c == CycleControl::stop) break;
    clock_.advance(period_);
  }
  s.simulated = cycle.now - start + period_;
  s.wall = std::chrono::duration_cast<Duration>(std::chrono::steady_clock::now() - wall_start);
  return s;
}

struct AsioScheduler::Impl {
  Impl(asio::io_context& io, const SteadyClock& c, Duration p, DeadlineSleeper* s)
      : timer(io), clock(c), period(p), sleeper(s) {}

  void arm() {
    if (sleeper) return;  // run_until_done() sleeps to the deadline itself
    timer.expires_at(clock.to_steady(deadline));
    timer.async_wait([this](const std::error_code& ec) { on_timer(ec); });
  }

  void on_timer(const std::error_code& ec) {
    if (ec || stop_requested) {
      finish();
      return;
    }
    on_wake(clock.now());
  }

  // `woke`: when the thread came back from the wait (the latency sample).
  void on_wake(TimePoint woke) {
    if (stop_requested) {
      finish();
      return;
    }
    stats.wake_latency.add(woke - deadline);
    ++stats.cycles;
    const CycleControl c = fn(CycleTime{deadline, period});
    const TimePoint done = clock.now();
    stats.max_cycle_work = std::max(stats.max_cycle_work, done - woke);
    deadline += period;
    if (done > deadline) {
      // The work ran past the next deadline: keep the absolute grid (no drift) and skip the
      // deadlines that already passed instead of running cycles back to back.
      ++stats.overruns;
      const auto behind = (done - deadline) / period + 1;
      stats.skipped_cycles += static_cast<std::uint64_t>(behind);
      deadline += period * behind;
    }
    if (c == CycleControl::stop || stats.cycles >= max_cycles || stop_requested) {
      finish();
      return;
    }
    arm();
  }

  void finish() {
    if (finished) return;
    finished = true;
    stats.simulated = deadline - (start + period);
    stats.wall = clock.now() - start;
    if (on_done) on_done(stats);
  }

  asio::io_context& io() { return static_cast<asio::io_context&>(timer.get_executor().context()); }

  void run_until_done() {
    auto& ctx = io();
    ctx.restart();
    if (!sleeper) {
      while (!finished && ctx.run_one() > 0) {
      }
      return;
    }
    // Keep the context from running out of work (which would stop it, and a stopped context
    // runs no handler posted later) while the sleeper, not the context, waits for deadlines.
    auto guard = asio::make_work_guard(ctx);
    while (!finished) {
      ctx.poll();  // I/O that became ready during the cycle (and the signal handlers)
      if (finished) break;
      if (stop_requested) {
        finish();
        break;
      }
      sleeper->sleep_until(deadline);
      const TimePoint woke = clock.now();
      ctx.poll();  // what arrived during the sleep, so the cycle sees the freshest data
      if (finished) break;
      on_wake(woke);
    }
  }

  asio::steady_timer timer;
  const SteadyClock& clock;
  Duration period;
  DeadlineSleeper* sleeper = nullptr;
  CycleFunction fn;
  std::function<void(const SchedulerStats&)> on_done;
  std::uint64_t max_cycles = 0;
  TimePoint start{};
  TimePoint deadline{};
  SchedulerStats stats;
  bool stop_requested = false;
  bool finished = true;
};

AsioScheduler::AsioScheduler(asio::io_context& io, const SteadyClock& clock, Duration period, DeadlineSleeper* sleeper)
    : impl_(std::make_unique<Impl>(io, clock, period > Duration::zero() ? period : std::chrono::milliseconds(1),
                                   sleeper)) {}

AsioScheduler::~AsioScheduler() = default;

void AsioScheduler::async_run(CycleFunction fn, std::function<void(const SchedulerStats&)> on_done,
                              std::uint64_t max_cycles) {
  auto& m = *impl_;
  m.fn = std::move(fn);
  m.on_done = std::move(on_done);
  m.max_cycles = max_cycles;
  m.stats = SchedulerStats{};
  m.stats.virtual_time = false;
  m.stats.period = m.period;
  m.stop_requested = false;
  m.finished = false;
  m.start = m.clock.now();
  m.deadline = m.start + m.period;
  m.arm();
}

void AsioScheduler::stop() noexcept {
  impl_->stop_requested = true;
  impl_->timer.cancel();
}

SchedulerStats AsioScheduler::run(CycleFunction fn, std::uint64_t max_cycles) {
  SchedulerStats out;
  async_run(
      std::move(fn), [&out](const SchedulerStats& s) { out = s; }, max_cycles);
  run_until_done();
  return out;
}

void AsioScheduler::run_until_done() {
  impl_->run_until_done();
}

const SchedulerStats& AsioScheduler::stats() const noexcept {
  return impl_->stats;
}

}  // namespace hil::runtime
