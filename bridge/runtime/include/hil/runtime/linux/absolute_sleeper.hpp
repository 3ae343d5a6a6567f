// SPDX-License-Identifier: MIT
#pragma once
// DeadlineSleeper on Linux: clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME) until the deadline
// (the steady clock is CLOCK_MONOTONIC), as cyclictest and LinuxCNC wait. An absolute wake-up
// never drifts and is not lengthened by the time spent computing the sleep; EINTR (a signal
// for the io_context's signal_set) resumes the same absolute sleep.

#include "hil/runtime/scheduler.hpp"

namespace hil::runtime::linux_rt {

class AbsoluteSleeper final : public DeadlineSleeper {
 public:
  /// `clock` maps deadlines to CLOCK_MONOTONIC; must outlive the sleeper.
  explicit AbsoluteSleeper(const SteadyClock& clock) noexcept : clock_(clock) {}
  /// Blocks the calling thread until `deadline`; returns at once when it has passed.
  void sleep_until(TimePoint deadline) noexcept override;

 private:
  const SteadyClock& clock_;
};

/// Reduce the calling thread's timer slack to 1 ns (normal threads get 50 µs of slack by
/// default, which lengthens every wake-up; SCHED_FIFO threads have none).
void minimise_timer_slack() noexcept;

}  // namespace hil::runtime::linux_rt
