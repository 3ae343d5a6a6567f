// SPDX-License-Identifier: MIT
#include "hil/runtime/linux/absolute_sleeper.hpp"

#include <sys/prctl.h>

#include <cerrno>
#include <ctime>

namespace hil::runtime::linux_rt {

void AbsoluteSleeper::sleep_until(TimePoint deadline) noexcept {
  // libstdc++'s steady_clock is CLOCK_MONOTONIC, so its epoch is the kernel's.
  const auto since = clock_.to_steady(deadline).time_since_epoch();
  const auto ns = std::chrono::duration_cast<std::chrono::nanoseconds>(since).count();
  timespec ts{};
  ts.tv_sec = static_cast<time_t>(ns / 1'000'000'000);
  ts.tv_nsec = static_cast<long>(ns % 1'000'000'000);
  while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) == EINTR) {
  }
}

void minimise_timer_slack() noexcept {
  (void)prctl(PR_SET_TIMERSLACK, 1UL, 0UL, 0UL, 0UL);
}

}  // namespace hil::runtime::linux_rt
