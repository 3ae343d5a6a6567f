// SPDX-License-Identifier: MIT
#pragma once
// Trajectory planning (Ruckig-style: pure functions of state, target and limits; no clock).
// All positions in user units; limits as in limits.hpp. See docs/motion.md for the maths.

#include "hil/motion/limits.hpp"
#include "hil/motion/profile.hpp"

namespace hil::motion {

/// Time-optimal rest-to-rest move from `from` to `to` under symmetric limits: 7-phase S-curve
/// (trapezoid for jerk = inf), with the cases where the maximum acceleration and/or velocity are
/// not reached solved in closed form. O(1), no iteration.
void plan_rest_to_rest(double from, double to, const Limits& limits, Profile& out) noexcept;

/// Minimum duration of a rest-to-rest move of |distance| under `limits` (closed form).
[[nodiscard]] double rest_to_rest_duration(double distance, const Limits& limits) noexcept;

/// Move from any state (p, v, a) to rest at `target`, never exceeding `limits` (`from` must be
/// inside them; see the overload with `entry` otherwise). Time-optimal from rest; from motion it
/// takes the faster of "ramp to a cruise velocity vc, cruise, ramp to rest" (vc from
/// D(vc) = distance, solved by Newton steps on the closed-form D with its exact slope; a target
/// behind the braking point makes vc point backwards: the axis reverses) and, when decelerating
/// towards a target just beyond the braking point, "relax the deceleration, then brake"
/// (docs/motion.md). O(1) from rest; typically 3-6 closed-form evaluations from motion.
void plan_position(const State& from, double target, const Limits& limits, Profile& out) noexcept;

/// Catch a target that moves at constant velocity: it is at `target` at t = 0 and moves at
/// `target_velocity` (|target_velocity| < limits.velocity; clamped into the limit). The profile
/// ends on it (p = target + target_velocity * T, v = target_velocity, a = 0) and then follows
/// it (a profile continues at its end velocity): synchronising to a master axis, a flying
/// cut-off, cam engagement. Solved as plan_position in the target's frame, where the velocity
/// limit towards direction d is limits.velocity - d * target_velocity (so |v| <= limits.velocity
/// in the machine frame). `from` inside `limits`. target_velocity = 0 is plan_position.
void plan_moving_target(const State& from, double target, double target_velocity, const Limits& limits,
                        Profile& out) noexcept;

/// Reach `velocity` (signed) with zero acceleration from any state, then cruise on.
void plan_velocity(const State& from, double velocity, const Limits& limits, Profile& out) noexcept;

/// Re-planning with *lower* limits than the ones `from` was reached under: when `from` lies
/// outside `limits` (|a| above the new acceleration, or zeroing a under the new jerk would pass
/// the new velocity), first bring a to zero under `entry` (the higher limits the state was
/// planned with), velocity clamped into the new limit, then continue under `limits`.
void plan_position(const State& from, double target, const Limits& limits, const Limits& entry, Profile& out) noexcept;
void plan_velocity(const State& from, double velocity, const Limits& limits, const Limits& entry,
                   Profile& out) noexcept;
/// Where a stop under `limits` (entered under `entry`) comes to rest.
[[nodiscard]] double stop_position(const State& from, const Limits& limits, const Limits& entry) noexcept;

/// Position where a stop from `from` under `limits` comes to rest.
[[nodiscard]] double stop_position(const State& from, const Limits& limits) noexcept;

}  // namespace hil::motion
