// SPDX-License-Identifier: MIT
#pragma once
// Kinematic limits and direction choice of a move. Units are the axis' user units
// (mm, degree, ...): velocity in units/s, acceleration in units/s^2, jerk in units/s^3.

#include <cmath>
#include <limits>

namespace hil::motion {

/// Kinematic limits of one move. All three must be > 0. `jerk` = +infinity plans a trapezoidal
/// velocity profile (acceleration steps); any finite jerk plans a 7-phase S-curve.
struct Limits {
  double velocity = 0.0;                                  ///< units/s
  double acceleration = 0.0;                              ///< units/s^2
  double jerk = std::numeric_limits<double>::infinity();  ///< units/s^3; +inf -> trapezoid
  [[nodiscard]] bool jerk_limited() const noexcept { return std::isfinite(jerk); }
};

/// Direction rule of an absolute move on a rotary (modulo) axis. Linear axes ignore it.
enum class Direction {
  shortest,  ///< the shorter way round; a tie (exactly half a turn) goes positive
  positive,  ///< always increasing position (0..modulo ahead)
  negative,  ///< always decreasing position
};

}  // namespace hil::motion
