// SPDX-License-Identifier: MIT
// Step 6: supervision. Rules (WF 725/726 description, §4.3 MD 24/25/26/30/33):
// - in motion the following error must stay inside the motion window: the static window, or
//   (dynamic) s_limit = 1.5 * v / Kv clamped to [min_window (MD 26), max_window (MD 24)], v being
//   the programmed feed of the move (error 11);
// - when the set-point reaches the target the in-position timer starts (MD 30); the actual
//   position must enter +-in_position_window (MD 33) before it runs out (error 22); until then the
//   motion window still applies;
// - once in position, standstill monitoring is armed: |following error| <= standstill_window
//   (MD 25), else error 10.
#include "hil/motion/supervision.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

namespace hil::motion {

void Supervisor::start_move() noexcept {
  settling_ = false;
  standstill_armed_ = false;
  in_position_ = false;
}

void Supervisor::hold() noexcept {
  settling_ = false;
  standstill_armed_ = true;
  in_position_ = true;
}

double Supervisor::motion_window(const AxisConfig& config, double feed) noexcept {
  const auto& fe = config.following_error;
  if (!fe.dynamic) return fe.static_window;
  return std::clamp(1.5 * std::fabs(feed) / fe.kv_per_s, fe.min_window, fe.max_window);
}

hil::Fault Supervisor::check(const AxisConfig& c, double following_error, double feed, bool profile_running,
                             double target_error, hil::TimePoint now, bool path_supervised) {
  const double fe = std::fabs(following_error);
  if (profile_running) {
    settling_ = false;
    standstill_armed_ = false;
    in_position_ = false;
  } else if (!standstill_armed_) {
    if (!settling_) {
      settling_ = true;
      settle_start_ = now;
    }
    if (std::fabs(target_error) <= c.in_position_window) {
      settling_ = false;
      standstill_armed_ = true;
    } else if (now - settle_start_ > c.in_position_timeout) {
      settling_ = false;
      return hil::Fault{make_error_code(MotionFault::in_position_timeout),
                        fmt::format("axis '{}': target not reached: {:.6g} from the target after {} ms, in-position "
                                    "window +-{:.6g} (in_position_timeout)",
                                    c.name, target_error,
                                    std::chrono::duration_cast<std::chrono::milliseconds>(now - settle_start_).count(),
                                    c.in_position_window)};
    }
  }
  if (standstill_armed_) {
    in_position_ = std::fabs(target_error) <= c.in_position_window;
    if (fe > c.standstill_window) {
      return hil::Fault{make_error_code(MotionFault::standstill),
                        fmt::format("axis '{}': standstill following error {:.6g} exceeds the standstill window "
                                    "{:.6g} (standstill_window)",
                                    c.name, following_error, c.standstill_window)};
    }
    return {};
  }
  if (!path_supervised) return {};
  const double window = motion_window(c, feed);
  if (fe > window) {
    const auto& f = c.following_error;
    if (!f.dynamic) {
      return hil::Fault{make_error_code(MotionFault::following_error),
                        fmt::format("axis '{}': following error {:.6g} exceeds the static window {:.6g} "
                                    "(following_error.static_window)",
                                    c.name, following_error, window)};
    }
    return hil::Fault{
        make_error_code(MotionFault::following_error_dynamic),
        fmt::format("axis '{}': following error {:.6g} exceeds the speed-dependent window {:.6g} "
                    "(1.5 x feed {:.6g} / Kv {:.6g} 1/s, clamped to [{:.6g}, {:.6g}])",
                    c.name, following_error, window, std::fabs(feed), f.kv_per_s, f.min_window, f.max_window)};
  }
  return {};
}

}  // namespace hil::motion
