// SPDX-License-Identifier: MIT
// Step 2b of the trajectory maths: ramp distances and their slopes (see ramp_distance.hpp).
#include "ramp_distance.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "velocity_ramp.hpp"

namespace hil::motion::detail {
namespace {

constexpr double inf = std::numeric_limits<double>::infinity();

// Mirrored ramp w0, b0 -> w1 (w1 >= the stop velocity, so the acceleration rises first).
// Returns the mirrored distance, and the slopes with respect to w1 and to w0 (for b0 = 0).
struct Mirrored {
  double x = 0.0, dx_dw1 = 0.0, dx_dw0 = 0.0;
};

Mirrored mirrored(double w0, double b0, double w1, double A, double J) noexcept {
  // Two divisions per call: every other quotient is a product with these reciprocals (about a
  // third of the re-planning time was divisions; the rounding differs by an ulp at most).
  const double iJ = 1.0 / J, iA = 1.0 / A;
  const double dv = w1 - w0;
  Mirrored m;
  if (b0 == 0.0) {
    // From zero acceleration the ramp is point-symmetric: x = (w0 + w1) T / 2 with
    // T = dv/A + A/J (A reached) or 2 ap/J, ap = sqrt(J dv) (not reached); the common case of
    // every re-plan from a cruise and of the ramp back to rest.
    const double mean2 = w0 + w1;
    if (J * dv >= A * A) {
      const double half_t = 0.5 * (dv * iA + A * iJ);
      m.x = mean2 * half_t;
      m.dx_dw1 = half_t + 0.5 * mean2 * iA;
      m.dx_dw0 = half_t - 0.5 * mean2 * iA;
      return m;
    }
    const double ap = std::sqrt(std::max(0.0, J * dv));
    m.x = mean2 * ap * iJ;
    if (ap > 0.0) {
      const double k = 0.5 * mean2 / ap;
      m.dx_dw1 = ap * iJ + k;
      m.dx_dw0 = ap * iJ - k;
    } else {
      m.dx_dw1 = inf;
      m.dx_dw0 = -inf;
    }
    return m;
  }
  if (J * dv >= A * A - b0 * b0 * 0.5) {  // A reached: hold phase
    const double t1 = (A - b0) * iJ;
    const double x1 = t1 * (w0 + t1 * (b0 * 0.5 + t1 * J * (1.0 / 6.0)));
    const double wa = w0 + (A * A - b0 * b0) * (0.5 * iJ);
    const double wb = w1 - A * A * (0.5 * iJ);
    m.x = x1 + (wb * wb - wa * wa) * (0.5 * iA) + wb * A * iJ + A * A * A * (iJ * iJ * (1.0 / 3.0));
    m.dx_dw1 = wb * iA + A * iJ;
    m.dx_dw0 = t1 - wa * iA;  // b0 = 0: dx1/dw0 = t1, d(-wa^2/2A)/dw0 = -wa/A
    return m;
  }
  const double ap = std::max(std::sqrt(std::max(0.0, J * dv + b0 * b0 * 0.5)), std::max(b0, 0.0));
  const double t1 = (ap - b0) * iJ;
  const double x1 = t1 * (w0 + t1 * (b0 * 0.5 + t1 * J * (1.0 / 6.0)));
  const double wa = w0 + (ap * ap - b0 * b0) * (0.5 * iJ);
  m.x = x1 + wa * ap * iJ + ap * ap * ap * (iJ * iJ * (1.0 / 3.0));
  // dx/dap = 2 wa/J + 2 ap^2/J^2; dap/dw1 = J/(2 ap); for b0 = 0 the w0 slope also has
  // dap/dw0 = -J/(2 ap) and the explicit terms t1 + ap/J.
  const double dx_dap = 2.0 * wa * iJ + 2.0 * ap * ap * (iJ * iJ);
  const double dap_dw1 = ap > 0.0 ? J * 0.5 / ap : inf;
  m.dx_dw1 = ap > 0.0 ? dx_dap * dap_dw1 : inf;
  m.dx_dw0 = ap > 0.0 ? t1 + ap * iJ - dx_dap * dap_dw1 : -inf;
  return m;
}

}  // namespace

DistanceSlope ramp_to(double v0, double a0, double v1, const Limits& l) noexcept {
  const double A = l.acceleration;
  if (!l.jerk_limited()) {
    const double a = v1 >= v0 ? A : -A;
    return {(v1 * v1 - v0 * v0) / (2.0 * a), v1 / a};
  }
  const double J = l.jerk;
  const double v_stop = stop_velocity(v0, a0, J);
  if (std::fabs(v1 - v_stop) <= 1e-15 * std::max({1.0, std::fabs(v0), std::fabs(v1)})) {
    // As plan_ramp: only a0 is zeroed (no sub-femto velocity ramp), so the distance used to
    // size the cruise is the one the appended ramp covers.
    const double t = std::fabs(a0) * (1.0 / J), j = a0 > 0 ? -J : J;
    return {t * (v0 + t * (a0 / 2.0 + t * j * (1.0 / 6.0))), inf};
  }
  const double s = v1 >= v_stop ? 1.0 : -1.0;
  const Mirrored m = mirrored(s * v0, s * a0, s * v1, A, J);
  return {s * m.x, m.dx_dw1};
}

DistanceSlope ramp_from(double v0, double v1, const Limits& l) noexcept {
  const double A = l.acceleration;
  if (!l.jerk_limited()) {
    const double a = v1 >= v0 ? A : -A;
    return {(v1 * v1 - v0 * v0) / (2.0 * a), -v0 / a};
  }
  if (std::fabs(v1 - v0) <= 1e-15 * std::max({1.0, std::fabs(v0), std::fabs(v1)})) return {0.0, -inf};
  const double s = v1 >= v0 ? 1.0 : -1.0;
  const Mirrored m = mirrored(s * v0, 0.0, s * v1, A, l.jerk);
  return {s * m.x, m.dx_dw0};
}

}  // namespace hil::motion::detail
