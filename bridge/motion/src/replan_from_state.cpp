// SPDX-License-Identifier: MIT
// Step 5 of the trajectory maths: moves that start in motion (new target while moving,
// velocity moves, stops).
//
// Target from a state (p0, v0, a0): brake = ramp(v0, a0 -> 0) stops at p_stop. With the
// direction dir = sign(target - p_stop), the family
//     ramp(v0, a0 -> dir vc), cruise, ramp(dir vc -> 0)
// covers, for vc >= max(dir v_stop, 0) (v_stop = velocity after zeroing a0 at once), a distance
// D(vc) that grows monotonically with vc (every ramp accelerates towards dir; a higher vc gives a
// pointwise higher speed). So: vc = V if D(V) <= d (cruise fills the rest); else bisection on vc
// (D is continuous) and the cruise absorbs the last residual so the end is exact. When even the
// smallest of those members overshoots (the axis is already decelerating and the target sits
// between the braking point and D(vc_min)), vc is searched below v_stop instead: the axis slows
// to vc without stopping (D(0) is the braking distance, so a crossing exists). Never exceeds the
// limits; time-optimal from rest (then it is exactly plan_rest_to_rest).
#include <algorithm>
#include <cmath>

#include "hil/motion/plan.hpp"
#include "velocity_ramp.hpp"

namespace hil::motion {

using detail::append_ramp;
using detail::plan_ramp;

namespace {

// Appends the move from out.current() to rest at `target` under `limits`.
void append_position(Profile& out, double target, const Limits& limits) noexcept {
  const State from = out.current();
  if (from.v == 0.0 && from.a == 0.0) {
    detail::append_rest_to_rest(out, target, limits);
    return;
  }
  const detail::Ramp brake = plan_ramp(from.v, from.a, 0.0, limits);
  const double p_stop = from.p + brake.distance;
  const double gap = target - p_stop;
  if (std::fabs(gap) <= 1e-12 * std::max(1.0, std::fabs(target))) {
    append_ramp(brake, out);
    return;
  }
  const double dir = gap > 0 ? 1.0 : -1.0;
  const double dn = dir * (target - from.p);
  // D(vc): normalised distance of ramp to dir*vc and back to rest, no cruise.
  const auto distance = [&](double vc) {
    return dir *
           (plan_ramp(from.v, from.a, dir * vc, limits).distance + plan_ramp(dir * vc, 0.0, 0.0, limits).distance);
  };
  const double vn = dir * from.v, an = dir * from.a;
  const double v_stop = limits.jerk_limited() ? vn + an * std::fabs(an) / (2.0 * limits.jerk) : vn;
  const double vmax = limits.velocity;
  const double vlo = std::clamp(v_stop, 0.0, vmax);
  // Bracket the crossing D(vc) = d. D(vlo) <= d: search [vlo, V] (monotone there). D(vlo) > d
  // (already decelerating, target just beyond the braking point): search [0, vlo], where
  // D(0) = braking distance < d; D is continuous, so bisection keeps D(lo) <= d < D(hi) and
  // converges on a crossing: the axis slows to vc without stopping, cruises, and stops on target.
  double lo = vlo, hi = vmax;
  double dlo = distance(vlo);
  if (dlo > dn) {
    const double d0 = distance(0.0);
    if (d0 > dn) {  // cannot happen analytically (d0 is the braking distance); stay safe
      append_ramp(brake, out);
      detail::append_rest_to_rest(out, target, limits);
      return;
    }
    lo = 0.0;
    hi = vlo;
    dlo = d0;
  }
  double vc = vmax;
  double dvc = hi == vmax ? distance(vmax) : dn + 1.0;
  if (dvc > dn) {
    dvc = dlo;
    for (int i = 0; i < 200 && hi - lo > 1e-15 * vmax; ++i) {
      const double mid = 0.5 * (lo + hi);
      const double dm = distance(mid);
      if (dm <= dn) {
        lo = mid;
        dvc = dm;
      } else {
        hi = mid;
      }
    }
    vc = lo;
  }
  append_ramp(plan_ramp(from.v, from.a, dir * vc, limits), out);
  if (vc > 0.0) {
    const double cruise = (dn - dvc) / vc;
    if (cruise > 0.0) out.append_accel(cruise, 0.0);
  }
  append_ramp(plan_ramp(dir * vc, 0.0, 0.0, limits), out);
}

bool outside(const State& s, const Limits& l) noexcept {
  constexpr double tol = 1e-12;
  if (std::fabs(s.a) > l.acceleration * (1 + tol)) return true;
  const double v_stop = l.jerk_limited() ? s.v + s.a * std::fabs(s.a) / (2.0 * l.jerk) : s.v;
  return std::fabs(v_stop) > l.velocity * (1 + tol) && std::fabs(v_stop) > std::fabs(s.v);
}

// Brings `from` inside `limits` using `entry`: a to zero, velocity clamped into the new limit.
void append_entry(Profile& out, const Limits& limits, const Limits& entry) noexcept {
  const State s = out.current();
  if (!outside(s, limits)) return;
  const double v_stop = entry.jerk_limited() ? s.v + s.a * std::fabs(s.a) / (2.0 * entry.jerk) : s.v;
  append_ramp(plan_ramp(s.v, s.a, std::clamp(v_stop, -limits.velocity, limits.velocity), entry), out);
  out.append_accel(0.0, 0.0);
}

}  // namespace

double stop_position(const State& from, const Limits& limits) noexcept {
  return from.p + plan_ramp(from.v, from.a, 0.0, limits).distance;
}

double stop_position(const State& from, const Limits& limits, const Limits& entry) noexcept {
  Profile p;
  plan_velocity(from, 0.0, limits, entry, p);
  return p.end().p;
}

void plan_velocity(const State& from, double velocity, const Limits& limits, Profile& out) noexcept {
  plan_velocity(from, velocity, limits, limits, out);
}

void plan_velocity(const State& from, double velocity, const Limits& limits, const Limits& entry,
                   Profile& out) noexcept {
  const double v1 = std::clamp(velocity, -limits.velocity, limits.velocity);
  out.reset(from);
  append_entry(out, limits, entry);
  const State s = out.current();
  append_ramp(plan_ramp(s.v, s.a, v1, limits), out);
  out.finish(State{out.current().p, v1, 0.0, 0.0});
}

void plan_position(const State& from, double target, const Limits& limits, Profile& out) noexcept {
  plan_position(from, target, limits, limits, out);
}

void plan_position(const State& from, double target, const Limits& limits, const Limits& entry, Profile& out) noexcept {
  out.reset(from);
  append_entry(out, limits, entry);
  append_position(out, target, limits);
  out.finish(State{target, 0.0, 0.0, 0.0});
}

}  // namespace hil::motion
