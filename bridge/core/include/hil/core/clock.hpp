// SPDX-License-Identifier: MIT
#pragma once
// Injected time. Everything that waits, times out or samples time takes a `const Clock&`
// (or is handed `now` by its caller); nothing reads the system clock behind the caller's back,
// so every test runs on a VirtualClock and never sleeps.

#include <chrono>
#include <cstdint>

namespace hil {

/// Nanoseconds since an arbitrary epoch (the clock's start). Monotonic.
using Duration = std::chrono::nanoseconds;

class Clock;
using TimePoint = std::chrono::time_point<Clock, Duration>;

/// Monotonic time source. Thread: `now()` is safe from any thread for both implementations.
class Clock {
 public:
  using duration = Duration;
  using rep = Duration::rep;
  using period = Duration::period;
  using time_point = TimePoint;
  static constexpr bool is_steady = true;

  virtual ~Clock() = default;
  [[nodiscard]] virtual TimePoint now() const noexcept = 0;
};

/// Wall-time monotonic clock (std::chrono::steady_clock), epoch = construction.
class SteadyClock final : public Clock {
 public:
  SteadyClock() noexcept : start_(std::chrono::steady_clock::now()) {}
  [[nodiscard]] TimePoint now() const noexcept override {
    return TimePoint{std::chrono::duration_cast<Duration>(std::chrono::steady_clock::now() - start_)};
  }
  /// The steady_clock instant that corresponds to `t` (for Asio timers on real time).
  [[nodiscard]] std::chrono::steady_clock::time_point to_steady(TimePoint t) const noexcept {
    return start_ + std::chrono::duration_cast<std::chrono::steady_clock::duration>(t.time_since_epoch());
  }

 private:
  std::chrono::steady_clock::time_point start_;
};

/// Clock that moves only when told to. Not thread-safe: tests and the virtual-time runner
/// own it on one thread.
class VirtualClock final : public Clock {
 public:
  explicit VirtualClock(TimePoint start = TimePoint{}) noexcept : now_(start) {}
  [[nodiscard]] TimePoint now() const noexcept override { return now_; }
  void advance(Duration d) noexcept { now_ += d; }
  /// Jump to `t`; time never goes backwards, an earlier `t` is ignored.
  void advance_to(TimePoint t) noexcept {
    if (t > now_) now_ = t;
  }

 private:
  TimePoint now_;
};

/// Seconds as double, for motion maths at the edge of the cyclic path.
[[nodiscard]] constexpr double to_seconds(Duration d) noexcept {
  return std::chrono::duration<double>(d).count();
}
[[nodiscard]] constexpr double to_seconds(TimePoint t) noexcept {
  return to_seconds(t.time_since_epoch());
}
[[nodiscard]] constexpr Duration from_seconds(double s) noexcept {
  return std::chrono::duration_cast<Duration>(std::chrono::duration<double>(s));
}

}  // namespace hil
