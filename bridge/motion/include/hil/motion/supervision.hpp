// SPDX-License-Identifier: MIT
#pragma once
// Following-error, in-position and standstill supervision of one axis (WF 725/726 MD 24, 25,
// 26, 30, 33 semantics; docs/motion.md). Pure: the caller passes the cycle's values and time.

#include "hil/core/clock.hpp"
#include "hil/core/fault.hpp"
#include "hil/motion/axis_config.hpp"

namespace hil::motion {

class Supervisor {
 public:
  Supervisor() = default;

  /// A new profile starts: in-position and standstill monitoring are disarmed.
  void start_move() noexcept;
  /// Holding still at the current position (after enable/reset): standstill armed at once.
  void hold() noexcept;

  /// One cycle. `following_error` = command - actual (units); `feed` = programmed |velocity| of
  /// the active move (units/s); `profile_running` while the set-point still moves;
  /// `target_error` = target - actual. Returns an empty Fault or the violation (MotionFault code,
  /// text naming the value, the window and its rule). `path_supervised` = false skips the motion
  /// window (a drive that generates its own profile watches its own following error); the
  /// in-position and standstill rules still apply.
  [[nodiscard]] hil::Fault check(const AxisConfig& config, double following_error, double feed, bool profile_running,
                                 double target_error, hil::TimePoint now, bool path_supervised = true);

  [[nodiscard]] bool in_position() const noexcept { return in_position_; }
  /// Following-error window in motion for programmed feed `feed`: the static window, or
  /// clamp(1.5 * feed / Kv, min_window, max_window) when dynamic.
  [[nodiscard]] static double motion_window(const AxisConfig& config, double feed) noexcept;

 private:
  bool settling_ = false;  ///< profile done, waiting for the in-position window
  bool standstill_armed_ = false;
  bool in_position_ = false;
  hil::TimePoint settle_start_{};
};

}  // namespace hil::motion
