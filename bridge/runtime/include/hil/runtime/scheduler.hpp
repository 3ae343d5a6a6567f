// SPDX-License-Identifier: MIT
#pragma once
// The cycle scheduler: calls one cycle function at a fixed period.
//
// - VirtualScheduler: on a hil::VirtualClock, as fast as the CPU allows (tests, `hilbridge test`,
//   `hilbridge run --virtual`). Cycle k runs at start + k * period exactly.
// - AsioScheduler: on an Asio io_context with a steady timer against hil::SteadyClock (real
//   time). Deadlines are absolute (start + k * period), so the cadence never drifts; a cycle
//   that ends after the next deadline is an overrun and the deadlines it missed are skipped
//   (counted). Wake-up latency (actual wake - deadline) goes into a LatencyHistogram. With a
//   DeadlineSleeper (real-time mode: clock_nanosleep(TIMER_ABSTIME), linux/absolute_sleeper.hpp)
//   the cycle thread sleeps to each deadline itself and polls the io_context before and after
//   the sleep instead of waiting in epoll for a timer.
//
// Both hand the cycle function the same CycleTime (`now` = the cycle's nominal deadline,
// `period` = the nominal period), so the same cycle code runs on either.

#include <cstdint>
#include <functional>
#include <limits>
#include <memory>

#include "hil/core/clock.hpp"
#include "hil/core/drive.hpp"
#include "hil/runtime/latency_histogram.hpp"

namespace asio {
class io_context;
}

namespace hil::runtime {

enum class CycleControl : std::uint8_t { proceed, stop };

/// Runs once per cycle on the scheduler's thread (the thread calling run() / io_context::run()).
/// Must not block; returns `stop` to end the run after this cycle.
using CycleFunction = std::function<CycleControl(const CycleTime&)>;

struct SchedulerStats {
  bool virtual_time = true;
  Duration period{};
  std::uint64_t cycles = 0;          ///< cycle functions called
  std::uint64_t overruns = 0;        ///< cycles that ended after the next deadline (real time)
  std::uint64_t skipped_cycles = 0;  ///< deadlines dropped after overruns (real time)
  LatencyHistogram wake_latency;     ///< real time: actual wake-up minus deadline
  Duration max_cycle_work{};         ///< real time: longest cycle function execution
  Duration simulated{};              ///< time covered by the cycles (cycles * period, plus skipped)
  Duration wall{};                   ///< wall time the run took (both modes)
};

class VirtualScheduler {
 public:
  /// `period` > 0. The clock is advanced by the scheduler only.
  VirtualScheduler(VirtualClock& clock, Duration period) noexcept;

  /// Run cycles at clock.now(), +period, ... until `fn` returns stop or `max_cycles` ran.
  /// Blocking; calls `fn` on this thread.
  SchedulerStats run(const CycleFunction& fn, std::uint64_t max_cycles = std::numeric_limits<std::uint64_t>::max());

 private:
  VirtualClock& clock_;
  Duration period_;
};

/// Blocks the cycle thread until a deadline (real-time wake-ups). Thread: the cycle thread.
class DeadlineSleeper {
 public:
  virtual ~DeadlineSleeper() = default;
  /// Return at `deadline` (as soon after as the system allows); at once when it has passed.
  virtual void sleep_until(TimePoint deadline) noexcept = 0;
};

class AsioScheduler {
 public:
  /// `io` runs the timer (and, typically, the transports' sockets); `clock` gives the deadlines.
  /// `sleeper` (optional, must outlive the scheduler): wait for deadlines with it instead of an
  /// Asio timer; ready I/O handlers then run right before and right after each sleep.
  AsioScheduler(asio::io_context& io, const SteadyClock& clock, Duration period, DeadlineSleeper* sleeper = nullptr);
  ~AsioScheduler();
  AsioScheduler(const AsioScheduler&) = delete;
  AsioScheduler& operator=(const AsioScheduler&) = delete;

  /// Start cycling: the first deadline is clock.now() + period. `fn` and `on_done` run on the
  /// io_context's thread; `on_done` once, after the last cycle (fn returned stop, stop() or
  /// `max_cycles`). Non-blocking.
  void async_run(CycleFunction fn, std::function<void(const SchedulerStats&)> on_done,
                 std::uint64_t max_cycles = std::numeric_limits<std::uint64_t>::max());
  /// Ask the run to end before the next cycle. Call on the io_context's thread (e.g. from a
  /// signal_set handler on the same context).
  void stop() noexcept;
  /// Run the io_context (and, with a sleeper, the sleeps) on this thread until the run started
  /// by async_run is done. Blocking.
  void run_until_done();
  /// async_run, then run_until_done(). Blocking.
  SchedulerStats run(CycleFunction fn, std::uint64_t max_cycles = std::numeric_limits<std::uint64_t>::max());

  [[nodiscard]] const SchedulerStats& stats() const noexcept;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace hil::runtime
