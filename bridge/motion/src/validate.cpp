// SPDX-License-Identifier: MIT
// Step 0: configuration checks (the WF 725/726 cross-field rules where they apply).
#include <cmath>

#include <fmt/format.h>

#include "hil/motion/axis_config.hpp"
#include "hil/motion/axis_status.hpp"
#include "hil/motion/scaling.hpp"

namespace hil::motion {
namespace {

bool positive(double v) {
  return std::isfinite(v) && v > 0.0;
}
bool non_negative(double v) {
  return std::isfinite(v) && v >= 0.0;
}

}  // namespace

std::expected<AxisConfig, std::string> validate(const AxisConfig& c) {
  const auto fail = [&](std::string_view field, auto value, std::string_view rule) {
    return std::unexpected(fmt::format("axis '{}': {} = {}: {}", c.name, field, value, rule));
  };
  if (c.name.empty()) return std::unexpected(std::string("axis name is empty: give every axis a name"));
  if (c.inc_per_unit.num <= 0) return fail("inc_per_unit.num", c.inc_per_unit.num, "must be > 0");
  if (c.inc_per_unit.den <= 0) return fail("inc_per_unit.den", c.inc_per_unit.den, "must be > 0");
  if (!positive(c.limits.velocity)) return fail("limits.velocity", c.limits.velocity, "must be > 0 (units/s)");
  if (!positive(c.limits.acceleration))
    return fail("limits.acceleration", c.limits.acceleration, "must be > 0 (units/s^2)");
  if (!(c.limits.jerk > 0.0))
    return fail("limits.jerk", c.limits.jerk, "must be > 0 (units/s^3) or inf for a trapezoid");
  if (!positive(c.quick_stop_deceleration) || c.quick_stop_deceleration < c.limits.acceleration)
    return fail("quick_stop_deceleration", c.quick_stop_deceleration, "must be >= limits.acceleration");
  if (!positive(c.jog_velocity) || c.jog_velocity > c.limits.velocity)
    return fail("jog_velocity", c.jog_velocity, "must be > 0 and <= limits.velocity");
  if (c.rotary) {
    if (!positive(c.modulo)) return fail("modulo", c.modulo, "must be > 0 (units per turn)");
    const double turn = c.modulo * static_cast<double>(c.inc_per_unit.num) / static_cast<double>(c.inc_per_unit.den);
    if (std::fabs(turn - std::round(turn)) > 1e-9 * std::max(1.0, turn) || turn < 1.0)
      return fail("modulo", c.modulo, "modulo * inc_per_unit must be a whole number of increments per turn");
    if (c.soft_limit_min || c.soft_limit_max)
      return fail("soft_limit", "set", "software limits are not supported on rotary axes; remove them");
  }
  if (c.soft_limit_min && !std::isfinite(*c.soft_limit_min))
    return fail("soft_limit_min", *c.soft_limit_min, "must be finite");
  if (c.soft_limit_max && !std::isfinite(*c.soft_limit_max))
    return fail("soft_limit_max", *c.soft_limit_max, "must be finite");
  if (c.soft_limit_min && c.soft_limit_max && !(*c.soft_limit_min < *c.soft_limit_max))
    return fail("soft_limit_min", *c.soft_limit_min, "must be < soft_limit_max");
  if (!non_negative(c.backlash)) return fail("backlash", c.backlash, "must be >= 0");
  const auto& fe = c.following_error;
  if (!fe.dynamic && !positive(fe.static_window))
    return fail("following_error.static_window", fe.static_window, "must be > 0");
  if (fe.dynamic) {
    if (!positive(fe.kv_per_s)) return fail("following_error.kv_per_s", fe.kv_per_s, "must be > 0 (1/s)");
    if (!positive(fe.min_window)) return fail("following_error.min_window", fe.min_window, "must be > 0");
    if (!positive(fe.max_window) || fe.max_window < fe.min_window)
      return fail("following_error.max_window", fe.max_window, "must be >= following_error.min_window");
  }
  if (!positive(c.standstill_window)) return fail("standstill_window", c.standstill_window, "must be > 0");
  if (!positive(c.in_position_window)) return fail("in_position_window", c.in_position_window, "must be > 0");
  // WF 725/726 MD 33 < MD 25: otherwise the standstill error fires each time the target is reached.
  if (c.in_position_window > c.standstill_window)
    return fail("in_position_window", c.in_position_window, "must be <= standstill_window (else every arrival faults)");
  if (c.in_position_timeout <= hil::Duration::zero())
    return fail("in_position_timeout", c.in_position_timeout.count(), "must be > 0 ns");
  if (c.enable_timeout <= hil::Duration::zero())
    return fail("enable_timeout", c.enable_timeout.count(), "must be > 0 ns");
  if (c.feedback_timeout <= hil::Duration::zero())
    return fail("feedback_timeout", c.feedback_timeout.count(), "must be > 0 ns");
  return c;
}

const char* to_string(AxisState s) noexcept {
  switch (s) {
    case AxisState::disabled:
      return "disabled";
    case AxisState::enabling:
      return "enabling";
    case AxisState::standstill:
      return "standstill";
    case AxisState::moving:
      return "moving";
    case AxisState::stopping:
      return "stopping";
    case AxisState::homing:
      return "homing";
    case AxisState::error:
      return "error";
  }
  return "unknown";
}

}  // namespace hil::motion
