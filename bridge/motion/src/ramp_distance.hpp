// SPDX-License-Identifier: MIT
#pragma once
// Internal: the distance a velocity ramp covers and its slope with respect to the velocity it
// is solved for, in closed form, for the re-planning root solve (replan_from_state.cpp).
// Same maths as plan_ramp (velocity_ramp.cpp), written per case as a polynomial in the peak
// acceleration so the slope is exact:
//   A reached (hold):  x = s (x1 + (wb^2 - wa^2) / (2A) + wb A/J + A^3/(3J^2)), dx/dv1 = wb/A + A/J
//   A not reached:     ap = sqrt(J dv + b0^2/2), x = s (x1(ap) + wa ap/J + ap^3/(3J^2)),
//                      dx/dv1 = wa/ap + ap/J
// with s the direction of the acceleration, (w0, b0) = s (v0, a0), wa/wb the velocities
// at the start/end of the hold (wa = w0 + (ap^2 - b0^2)/(2J), wb = s v1 - ap^2/(2J)).

#include "hil/motion/limits.hpp"

namespace hil::motion::detail {

struct DistanceSlope {
  double distance = 0.0;  ///< signed, units
  double slope = 0.0;     ///< d distance / d velocity, s (+inf at a sqrt branch point)
};

/// Ramp (v0, a0) -> (v1, 0): distance and d distance / d v1.
[[nodiscard]] DistanceSlope ramp_to(double v0, double a0, double v1, const Limits& l) noexcept;
/// Ramp (v0, 0) -> (v1, 0): distance and d distance / d v0.
[[nodiscard]] DistanceSlope ramp_from(double v0, double v1, const Limits& l) noexcept;

}  // namespace hil::motion::detail
