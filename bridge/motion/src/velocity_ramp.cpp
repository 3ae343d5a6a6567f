// SPDX-License-Identifier: MIT
// Step 2 of the trajectory maths: the velocity ramp from any (v0, a0) to (v1, 0).
//
// Finite jerk j, max acceleration A. Zeroing a0 at once (jerk -sign(a0) j) would end at
// v_stop = v0 + a0|a0|/(2j). The sign s of v1 - v_stop is the direction the acceleration must
// take. Mirrored by s (so the peak acceleration ap is positive), with dv = s(v1 - v0):
//   phase 1: a0 -> ap at jerk sign(ap - a0) j, gains (a0 + ap)|ap - a0| / (2j)
//   phase 2: hold ap for (dv - phase1 - phase3) / ap
//   phase 3: ap -> 0 at jerk -j, gains ap^2 / (2j)
// ap = A when phases 1 + 3 fit into dv; otherwise phase 2 vanishes and
// (ap^2 - a0^2)/(2j) + ap^2/(2j) = dv  =>  ap = sqrt(j dv + a0^2 / 2)  (>= a0 because v1 > v_stop).
#include "velocity_ramp.hpp"

#include <algorithm>
#include <cmath>

namespace hil::motion::detail {
namespace {

double integrate_distance(double v, double a, const Ramp& r) noexcept {
  if (r.step) return v * r.t[0] + r.accel * r.t[0] * r.t[0] / 2.0;
  double p = 0.0;
  for (int i = 0; i < 3; ++i) {
    const double t = r.t[i], jj = r.j[i];
    p += t * (v + t * (a / 2.0 + t * jj * (1.0 / 6.0)));
    v += t * (a + t * jj / 2.0);
    a += t * jj;
  }
  return p;
}

}  // namespace

Ramp plan_ramp(double v0, double a0, double v1, const Limits& limits) noexcept {
  Ramp r = ramp_shape(v0, a0, v1, limits);
  r.distance = integrate_distance(v0, a0, r);
  return r;
}

Ramp ramp_shape(double v0, double a0, double v1, const Limits& limits) noexcept {
  Ramp r;
  const double amax = limits.acceleration;
  const double scale = std::max({1.0, std::fabs(v0), std::fabs(v1)});
  if (!limits.jerk_limited()) {
    const double dv = v1 - v0;
    r.step = true;
    if (std::fabs(dv) > 1e-15 * scale) {
      r.accel = dv > 0 ? amax : -amax;
      r.t[0] = std::fabs(dv) / amax;
    }
    r.duration = r.t[0];
    return r;
  }
  const double j = limits.jerk;
  const double ij = 1.0 / j;  // one division; the quotients below are products with it
  const double v_stop = stop_velocity(v0, a0, j);
  const double dvs = v1 - v_stop;
  if (std::fabs(dvs) <= 1e-15 * scale) {
    r.t[0] = std::fabs(a0) * ij;
    r.j[0] = a0 > 0 ? -j : j;
  } else {
    const double s = dvs > 0 ? 1.0 : -1.0;
    const double a0m = s * a0;
    const double dv = s * (v1 - v0);
    const double dv1 = (a0m + amax) * std::fabs(amax - a0m) * (0.5 * ij);
    const double dv3 = amax * amax * (0.5 * ij);
    double ap = amax;
    double t2 = 0.0;
    if (dv1 + dv3 <= dv) {
      t2 = (dv - dv1 - dv3) / amax;
    } else {
      ap = std::sqrt(std::max(0.0, j * dv + a0m * a0m / 2.0));
      ap = std::max(ap, a0m);
    }
    r.t[0] = std::fabs(ap - a0m) * ij;
    r.j[0] = (ap >= a0m ? s : -s) * j;
    r.t[1] = t2;
    r.t[2] = ap * ij;
    r.j[2] = -s * j;
  }
  r.duration = r.t[0] + r.t[1] + r.t[2];
  return r;
}

void append_ramp(const Ramp& ramp, Profile& out) noexcept {
  if (ramp.step) {
    out.append_accel(ramp.t[0], ramp.accel);
    return;
  }
  out.append(ramp.t[0], ramp.j[0]);
  out.append(ramp.t[1], 0.0);
  out.append(ramp.t[2], ramp.j[2]);
}

}  // namespace hil::motion::detail
