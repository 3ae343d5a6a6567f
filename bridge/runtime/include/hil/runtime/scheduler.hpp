// SPDX-License-Identifier: MIT
#pragma once
// The cycle scheduler: calls one cycle function at a fixed period.
//
// - VirtualScheduler: on a hil::VirtualClock, as fast as the CPU allows (tests, `hilbridge test`,
//   `hilbridge run --virtual`). Cycle k runs at start + k * period exactly.
// - AsioScheduler: on an Asio io_context with a steady timer against hil::SteadyClock (real
//   time). Deadlines are absolute (start + k * period), so the cadence never drifts; a cycle
//   that ends after the next deadline is an overrun and the deadlines it missed are skipped
//   (counted). Wake-up latency (actual wake - deadline) goes into a LatencyHistogram.
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

class AsioScheduler {
 public:
  /// `io` runs the timer (and, typically, the transports' sockets); `clock` gives the deadlines.
  AsioScheduler(asio::io_context& io, const SteadyClock& clock, Duration period);
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
  /// async_run, then io.run() until done. Blocking.
  SchedulerStats run(CycleFunction fn, std::uint64_t max_cycles = std::numeric_limits<std::uint64_t>::max());

  [[nodiscard]] const SchedulerStats& stats() const noexcept;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace hil::runtime
