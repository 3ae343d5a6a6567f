// SPDX-License-Identifier: MIT
#pragma once
// Static configuration of one axis and its validation.

#include <chrono>
#include <expected>
#include <optional>
#include <string>

#include "hil/core/clock.hpp"
#include "hil/motion/limits.hpp"
#include "hil/motion/ratio.hpp"

namespace hil::motion {

/// What the axis does when supervision trips (WF 725/726: error -> "axis stops").
enum class FaultReaction {
  quick_stop,  ///< brake at `quick_stop_deceleration`, hold position, enabled
  stop,        ///< brake under the normal limits, hold position, enabled
  disable,     ///< request drive disable at once (coasts / drive's own reaction)
};

/// One axis. Distances in user units, times as hil::Duration.
struct AxisConfig {
  std::string name;
  Ratio inc_per_unit;                    ///< drive increments per user unit, exact
  bool rotary = false;                   ///< modulo axis: positions shown in [0, modulo)
  double modulo = 360.0;                 ///< units per turn (rotary only); modulo*num/den must be an integer
  Limits limits;                         ///< default limits of every move
  double quick_stop_deceleration = 0.0;  ///< units/s^2, >= limits.acceleration
  double jog_velocity = 0.0;             ///< units/s, 0 < jog_velocity <= limits.velocity
  std::optional<double> soft_limit_min, soft_limit_max;  ///< linear axes only; stop exactly there
  double backlash = 0.0;                                 ///< units, added to the drive command after a reversal
  struct FollowingError {
    double static_window = 0.0;  ///< units; used in motion when `dynamic` is false (> 0)
    bool dynamic = false;        ///< WF 725/726 MD 24/26: window = clamp(1.5*v/Kv, min, max)
    double kv_per_s = 0.0;       ///< position loop gain Kv in 1/s (v/Kv = steady following error)
    double min_window = 0.0;     ///< units (MD 26)
    double max_window = 0.0;     ///< units (MD 24)
  } following_error;
  double standstill_window = 0.0;                                     ///< units (MD 25); armed once in position
  double in_position_window = 0.0;                                    ///< units (MD 33), <= standstill_window
  hil::Duration in_position_timeout{std::chrono::milliseconds(500)};  ///< MD 30
  FaultReaction reaction = FaultReaction::quick_stop;
  hil::Duration enable_timeout{std::chrono::seconds(2)};          ///< enable() -> operation_enabled
  hil::Duration feedback_timeout{std::chrono::milliseconds(20)};  ///< feedback().age above -> drive_lost
};

/// Checks a configuration; returns it unchanged when every field makes sense, otherwise a message
/// naming the field, the value and the rule ("axis 'x': limits.jerk = -3: must be > 0 or inf").
[[nodiscard]] std::expected<AxisConfig, std::string> validate(const AxisConfig& config);

}  // namespace hil::motion
