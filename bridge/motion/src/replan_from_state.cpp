// SPDX-License-Identifier: MIT
// Step 5 of the trajectory maths: moves that start in motion (new target while moving,
// velocity moves, stops).
//
// Target from a state (p0, v0, a0): brake = ramp(v0, a0 -> 0) stops at p_stop. With the
// direction dir = sign(target - p_stop), the family
//     ramp(v0, a0 -> dir vc), cruise, ramp(dir vc -> 0)
// covers, for vc >= max(dir v_stop, 0) (v_stop = velocity after zeroing a0 at once), a distance
// D(vc) that grows monotonically with vc (every ramp accelerates towards dir; a higher vc gives a
// pointwise higher speed). So: vc = V if D(V) <= d (cruise fills the rest); else the crossing
// D(vc) = d, solved by safeguarded Newton steps on D in closed form with its exact slope
// (ramp_distance.hpp; 3-6 steps, no bisection over the range), and the cruise absorbs the last
// residual so the end is exact. When even the
// smallest of those members overshoots (the axis is already decelerating and the target sits
// between the braking point and D(vc_min)), vc is searched below v_stop instead: the axis slows
// to vc without stopping (D(0) is the braking distance, so a crossing exists). Never exceeds the
// limits; time-optimal from rest (then it is exactly plan_rest_to_rest).
#include <algorithm>
#include <cmath>
#include <limits>

#include "hil/motion/plan.hpp"
#include "ramp_distance.hpp"
#include "velocity_ramp.hpp"

namespace hil::motion {

using detail::append_ramp;
using detail::DistanceSlope;
using detail::plan_ramp;
using detail::ramp_from;
using detail::ramp_shape;
using detail::ramp_to;

namespace {

struct Crossing {
  double v = 0.0;         ///< cruise velocity with D(v) <= d (as close as doubles allow)
  double distance = 0.0;  ///< D(v)
};

// Root of the monotone, continuous D(v) = d on [lo, hi] with D(lo) <= d < D(hi): Newton steps
// on the closed-form D and its exact slope, kept inside the shrinking bracket (a step that
// would leave it, or a flat or infinite slope, falls back to the secant of the bracket, then
// to halving). D is piecewise a quadratic or a polynomial in sqrt(v - v_branch), so Newton
// converges in 3-6 steps; the 60-step cap is a guard for degenerate limits only.
template <class F>
Crossing solve_crossing(const F& distance, double d, double lo, double hi, double dlo, double dhi, double scale,
                        double slope_hi = 0.0, double guess = -1.0) noexcept {
  Crossing best{lo, dlo};
  const double tol_x = 1e-15 * scale;
  const double tol_d = 4e-16 * std::max(1.0, std::fabs(d));
  // First guess: a Newton step down from hi when its slope is known (D is convex on most of
  // its pieces, so this lands close above the root), else the secant of the bracket.
  double v = dhi > dlo ? lo + (hi - lo) * (d - dlo) / (dhi - dlo) : 0.5 * (lo + hi);
  if (slope_hi > 0.0 && slope_hi < std::numeric_limits<double>::infinity()) {
    const double newton = hi - (dhi - d) / slope_hi;
    if (newton > lo && newton < hi) v = newton;
  }
  if (guess > lo && guess < hi) v = guess;
  bool secant_last = true;
  for (int i = 0; i < 60; ++i) {
    const DistanceSlope e = distance(v);
    const double f = e.distance - d;
    if (f <= 0.0) {
      lo = v;
      dlo = e.distance;
      best = {v, e.distance};
      if (f >= -tol_d) break;
    } else {
      hi = v;
      dhi = e.distance;
      if (f <= tol_d) {  // a hair beyond: the cruise is skipped and finish() absorbs it
        best = {v, e.distance};
        break;
      }
    }
    if (hi - lo <= tol_x) break;
    double next = v - f / e.slope;
    if (!(e.slope > 0.0) || !(next > lo && next < hi)) {
      // Secant of the bracket once, halving if the secant stalls twice in a row.
      next = (!secant_last && dhi > dlo) ? lo + (hi - lo) * (d - dlo) / (dhi - dlo) : 0.5 * (lo + hi);
      secant_last = !secant_last;
      if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    }
    v = next;
  }
  return best;
}

// The crossing in closed form on the piece where both ramps reach A (three quarters of the
// crossings in the benchmark's cases): there, with (w0, b0) the normalised start,
//   D(vc) = vc^2/A + vc A/J + c,  c = x1 - wa^2/(2A) - A^3/(24 J^2)
// (x1, wa: the first jerk phase's distance and end velocity, as in ramp_distance.cpp; from rest
// c = 0, the rest-to-rest distance vc T). Returns the root of D(vc) = d when it lies on that
// piece, else -1. Written without cancellation: vc = 2e / (A/J + sqrt((A/J)^2 + 4e/A)), e = d - c.
double both_reached_root(double w0, double b0, double d, const Limits& l) noexcept {
  const double A = l.acceleration, J = l.jerk, iJ = 1.0 / J;
  const double t1 = (A - b0) * iJ;
  const double x1 = t1 * (w0 + t1 * (b0 * 0.5 + t1 * J * (1.0 / 6.0)));
  const double wa = w0 + (A * A - b0 * b0) * (0.5 * iJ);
  const double c = x1 - wa * wa * (0.5 / A) - A * A * A * (iJ * iJ * (1.0 / 24.0));
  const double e = d - c;
  if (!(e > 0.0)) return -1.0;
  const double b = A * iJ;
  const double vc = 2.0 * e / (b + std::sqrt(b * b + 4.0 * e / A));
  if (J * (vc - w0) < A * A - b0 * b0 * 0.5 || J * vc < A * A) return -1.0;
  return vc;
}

// The other candidate when the axis is decelerating towards a target just beyond its braking
// point (normalised: vn >= 0 moving towards it, an < 0, D_brake < dn < D(v_stop)): instead of
// slowing to vc, touching a = 0 and braking again (the family above), relax the deceleration
// from an to am in [an, 0] at jerk +J, then brake to rest: E(am) = x_relax(am) + brake(v1, am),
// E(an) = the braking distance < dn, E(0) = zero a then brake (>= dn), E continuous: solve
// E(am) = dn. Appends it and returns true when it is faster than the family's member (vc).
bool append_relaxed_brake(Profile& out, double vn, double an, double dn, double d_brake, double dir, double target_v,
                          const Limits& limits, double vc, double dvc, const State& rel) noexcept {
  const double J = limits.jerk;
  const auto relax = [&](double am) {
    const double t1 = (am - an) / J;
    const double v1 = vn + (am * am - an * an) / (2.0 * J);
    const double x1 = t1 * (vn + t1 * (an / 2.0 + t1 * J * (1.0 / 6.0)));
    return DistanceSlope{x1 + ramp_to(v1, am, 0.0, limits).distance, std::numeric_limits<double>::quiet_NaN()};
  };
  const double e0 = relax(0.0).distance;
  if (!(e0 > dn) || !(d_brake < dn)) return false;
  const Crossing c = solve_crossing(relax, dn, an, 0.0, d_brake, e0, limits.acceleration);
  const double am = c.v;
  const double t1 = (am - an) / J;
  const double v1 = vn + (am * am - an * an) / (2.0 * J);
  const double t_relaxed = t1 + ramp_shape(v1, am, 0.0, limits).duration;
  const double cruise = vc > 0.0 ? std::max(0.0, (dn - dvc) / vc) : 0.0;
  const double t_family =
      ramp_shape(rel.v, rel.a, dir * vc, limits).duration + cruise + ramp_shape(dir * vc, 0.0, 0.0, limits).duration;
  if (!(t_relaxed < t_family)) return false;
  out.append(t1, dir * J);
  const State cur = out.current();
  append_ramp(ramp_shape(cur.v - target_v, cur.a, 0.0, limits), out);
  return true;
}

// Appends the move from out.current() onto the target that is at `target` at profile time 0 and
// moves at `target_v` (0: a target at rest), under `limits` (|target_v| < limits.velocity).
// Solved in the target's frame: relative position x = p - target(t), relative velocity
// u = v - target_v, same acceleration and jerk; there the target is at rest at 0, and the
// velocity limit towards dir is V - dir target_v (so the absolute velocity stays within +-V).
// The jerk and cruise segments appended are the same in both frames.
void append_position(Profile& out, double target, double target_v, const Limits& limits) noexcept {
  const State cur = out.current();
  if (target_v == 0.0 && cur.v == 0.0 && cur.a == 0.0) {
    detail::append_rest_to_rest(out, target, limits);
    return;
  }
  const State from{cur.p - (target + target_v * out.duration()), cur.v - target_v, cur.a, 0.0};
  const double p_stop = from.p + ramp_to(from.v, from.a, 0.0, limits).distance;
  const double gap = -p_stop;
  if (std::fabs(gap) <= 1e-12 * std::max(1.0, std::fabs(target))) {
    append_ramp(ramp_shape(from.v, from.a, 0.0, limits), out);
    return;
  }
  const double dir = gap > 0 ? 1.0 : -1.0;
  const double dn = -dir * from.p;
  // D(vc): normalised distance of ramp to dir*vc and back to rest, no cruise; with its slope.
  const auto distance = [&](double vc) {
    const DistanceSlope r1 = ramp_to(from.v, from.a, dir * vc, limits);
    const DistanceSlope r2 = ramp_from(dir * vc, 0.0, limits);
    // d/dvc of dir * (x1(dir vc) + x2(dir vc)) = slope1 + slope2 (dir^2 = 1).
    return DistanceSlope{dir * (r1.distance + r2.distance), r1.slope + r2.slope};
  };
  const double vn = dir * from.v, an = dir * from.a;
  const double v_stop = limits.jerk_limited() ? detail::stop_velocity(vn, an, limits.jerk) : vn;
  const double vmax = std::max(limits.velocity - dir * target_v, 0.0);
  const double vlo = std::clamp(v_stop, 0.0, vmax);
  // Bracket the crossing D(vc) = d. D(vlo) <= d: search [vlo, V] (monotone there). D(vlo) > d
  // (already decelerating, target just beyond the braking point): search [0, vlo], where
  // D(0) = braking distance < d; D is continuous, so a crossing exists: the axis slows to vc
  // without stopping, cruises, and stops on target.
  // D(V) <= d (the common case): the cruise at V fills the rest, nothing to solve.
  double vc = vmax;
  const DistanceSlope at_vmax = distance(vmax);
  double dvc = at_vmax.distance;
  double d_brake = 0.0;
  bool slowing = false;
  if (dvc > dn) {
    double lo = vlo, hi = vmax, dhi = dvc, slope_hi = at_vmax.slope;
    double dlo = distance(vlo).distance;
    if (dlo > dn) {
      slowing = true;
      const double d0 = distance(0.0).distance;
      if (d0 > dn) {  // cannot happen analytically (d0 is the braking distance); stay safe
        append_ramp(ramp_shape(from.v, from.a, 0.0, limits), out);
        append_position(out, target, target_v, limits);
        return;
      }
      hi = vlo;
      dhi = dlo;
      slope_hi = 0.0;
      lo = 0.0;
      dlo = d0;
      d_brake = d0;
    }
    const Crossing c = solve_crossing(distance, dn, lo, hi, dlo, dhi, vmax, slope_hi,
                                      !slowing && limits.jerk_limited() ? both_reached_root(vn, an, dn, limits) : -1.0);
    vc = c.v;
    dvc = c.distance;
  }
  if (slowing && limits.jerk_limited() && an < 0.0 &&
      append_relaxed_brake(out, vn, an, dn, d_brake, dir, target_v, limits, vc, dvc, from))
    return;
  append_ramp(ramp_shape(from.v, from.a, dir * vc, limits), out);
  if (vc > 0.0) {
    const double cruise = (dn - dvc) / vc;
    if (cruise > 0.0) out.append_accel(cruise, 0.0);
  }
  append_ramp(ramp_shape(dir * vc, 0.0, 0.0, limits), out);
}

bool outside(const State& s, const Limits& l) noexcept {
  constexpr double tol = 1e-12;
  if (std::fabs(s.a) > l.acceleration * (1 + tol)) return true;
  const double v_stop = l.jerk_limited() ? detail::stop_velocity(s.v, s.a, l.jerk) : s.v;
  return std::fabs(v_stop) > l.velocity * (1 + tol) && std::fabs(v_stop) > std::fabs(s.v);
}

// Brings `from` inside `limits` using `entry`: a to zero, velocity clamped into the new limit.
void append_entry(Profile& out, const Limits& limits, const Limits& entry) noexcept {
  const State s = out.current();
  if (!outside(s, limits)) return;
  const double v_stop = entry.jerk_limited() ? detail::stop_velocity(s.v, s.a, entry.jerk) : s.v;
  append_ramp(ramp_shape(s.v, s.a, std::clamp(v_stop, -limits.velocity, limits.velocity), entry), out);
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
  append_ramp(ramp_shape(s.v, s.a, v1, limits), out);
  out.finish(State{out.current().p, v1, 0.0, 0.0});
}

void plan_position(const State& from, double target, const Limits& limits, Profile& out) noexcept {
  plan_position(from, target, limits, limits, out);
}

void plan_position(const State& from, double target, const Limits& limits, const Limits& entry, Profile& out) noexcept {
  out.reset(from);
  append_entry(out, limits, entry);
  append_position(out, target, 0.0, limits);
  out.finish(State{target, 0.0, 0.0, 0.0});
}

void plan_moving_target(const State& from, double target, double target_velocity, const Limits& limits,
                        Profile& out) noexcept {
  const double vt = std::clamp(target_velocity, -limits.velocity, limits.velocity);
  out.reset(from);
  append_entry(out, limits, limits);
  append_position(out, target, vt, limits);
  const double t = out.duration();
  out.finish(State{target + vt * t, vt, 0.0, 0.0});
}

}  // namespace hil::motion
