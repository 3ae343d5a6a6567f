// SPDX-License-Identifier: MIT
#pragma once
// Internal: the jerk-limited velocity change, the building block of every profile.

#include "hil/motion/limits.hpp"
#include "hil/motion/profile.hpp"

namespace hil::motion::detail {

/// Change velocity from (v0, a0) to v1 with zero final acceleration: up to three phases
/// (jerk towards the peak acceleration, hold it, jerk back to zero); one acceleration step for
/// trapezoidal limits.
struct Ramp {
  double t[3] = {0.0, 0.0, 0.0};  ///< phase durations, s
  double j[3] = {0.0, 0.0, 0.0};  ///< phase jerks (finite jerk)
  double accel = 0.0;             ///< trapezoid: the constant acceleration of phase 0
  bool step = false;              ///< trapezoid (jerk = inf)
  double duration = 0.0;          ///< s
  double distance = 0.0;          ///< units travelled, signed
};

/// Velocity reached by zeroing the acceleration a0 at once under jerk j. One expression for
/// every caller: the planner compares velocities with this one to the last bit.
[[nodiscard]] inline double stop_velocity(double v0, double a0, double j) noexcept {
  return v0 + a0 * (a0 < 0 ? -a0 : a0) * (0.5 * (1.0 / j));
}

[[nodiscard]] Ramp plan_ramp(double v0, double a0, double v1, const Limits& limits) noexcept;
/// plan_ramp without the distance (left 0): for ramps that are only appended, where the
/// profile integrates the segments anyway.
[[nodiscard]] Ramp ramp_shape(double v0, double a0, double v1, const Limits& limits) noexcept;
void append_ramp(const Ramp& ramp, Profile& out) noexcept;
/// Appends a time-optimal rest-to-rest move from the profile's current position (at rest) to `to`.
void append_rest_to_rest(Profile& out, double to, const Limits& limits) noexcept;

}  // namespace hil::motion::detail
