// SPDX-License-Identifier: MIT
// Step 3 of the trajectory maths: the time-optimal rest-to-rest move (closed form).
//
// Under symmetric limits (V, A, J) the optimum is an acceleration ramp to a peak velocity vp, a
// cruise at vp, and the mirrored deceleration ramp. The ramp from rest to vp takes
//   T(vp) = vp/A + A/J      if vp >= A^2/J   (A reached: 7-phase case)
//   T(vp) = 2 sqrt(vp/J)    otherwise        (A not reached)
// and covers vp T(vp) / 2. So vp = V when V T(V) <= d (V reached, cruise (d - V T(V)) / V);
// otherwise vp T(vp) = d, solved per case:
//   A reached:      vp^2/A + vp A/J = d  -> vp = 2 d A / (A^2/J + sqrt(A^4/J^2 + 4 d A))
//   A not reached:  2 J t^3 = d with t = sqrt(vp/J) -> vp = J (d / (2J))^(2/3)
// Trapezoid (J = inf): T(vp) = vp / A and vp = min(V, sqrt(d A)).
#include <algorithm>
#include <cmath>

#include "hil/motion/plan.hpp"
#include "velocity_ramp.hpp"

namespace hil::motion {
namespace {

double ramp_time(double vp, const Limits& l) noexcept {
  if (!l.jerk_limited()) return vp / l.acceleration;
  const double a = l.acceleration, j = l.jerk;
  return vp * j >= a * a ? vp / a + a / j : 2.0 * std::sqrt(vp / j);
}

double peak_velocity(double d, const Limits& l) noexcept {
  const double vmax = l.velocity, a = l.acceleration;
  if (!l.jerk_limited()) return std::min(vmax, std::sqrt(d * a));
  if (vmax * ramp_time(vmax, l) <= d) return vmax;
  const double j = l.jerk;
  const double b = a * a / j;
  const double vp = 2.0 * d * a / (b + std::sqrt(b * b + 4.0 * d * a));
  if (vp >= b) return std::min(vp, vmax);
  const double t = std::cbrt(d / (2.0 * j));
  return std::min(j * t * t, vmax);
}

}  // namespace

double rest_to_rest_duration(double distance, const Limits& limits) noexcept {
  const double d = std::fabs(distance);
  if (d == 0.0) return 0.0;
  const double vp = peak_velocity(d, limits);
  const double tr = ramp_time(vp, limits);
  return 2.0 * tr + std::max(0.0, (d - vp * tr) / vp);
}

namespace detail {

void append_rest_to_rest(Profile& out, double to, const Limits& limits) noexcept {
  const double from = out.current().p;
  const double d = std::fabs(to - from);
  if (d == 0.0) return;
  const double s = to > from ? 1.0 : -1.0;
  const double vp = peak_velocity(d, limits);
  const Ramp up = plan_ramp(0.0, 0.0, s * vp, limits);
  append_ramp(up, out);
  const double cruise = (d - 2.0 * std::fabs(up.distance)) / vp;
  if (cruise > 0.0) out.append_accel(cruise, 0.0);
  append_ramp(plan_ramp(s * vp, 0.0, 0.0, limits), out);
}

}  // namespace detail

void plan_rest_to_rest(double from, double to, const Limits& limits, Profile& out) noexcept {
  out.reset(State{from, 0.0, 0.0, 0.0});
  detail::append_rest_to_rest(out, to, limits);
  out.finish(State{to, 0.0, 0.0, 0.0});
}

}  // namespace hil::motion
