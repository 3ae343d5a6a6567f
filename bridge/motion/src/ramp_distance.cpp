// SPDX-License-Identifier: MIT
// Step 2b of the trajectory maths: ramp distances and their slopes (see ramp_distance.hpp).
#include "ramp_distance.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace hil::motion::detail {
namespace {

constexpr double inf = std::numeric_limits<double>::infinity();

// Mirrored ramp w0, b0 -> w1 (w1 >= the stop velocity, so the acceleration rises first).
// Returns the mirrored distance, and the slopes with respect to w1 and to w0 (for b0 = 0).
struct Mirrored {
  double x = 0.0, dx_dw1 = 0.0, dx_dw0 = 0.0;
};

Mirrored mirrored(double w0, double b0, double w1, double A, double J) noexcept {
  const double dv = w1 - w0;
  Mirrored m;
  if (J * dv >= A * A - b0 * b0 / 2.0) {  // A reached: hold phase
    const double t1 = (A - b0) / J;
    const double x1 = t1 * (w0 + t1 * (b0 / 2.0 + t1 * J / 6.0));
    const double wa = w0 + (A * A - b0 * b0) / (2.0 * J);
    const double wb = w1 - A * A / (2.0 * J);
    m.x = x1 + (wb * wb - wa * wa) / (2.0 * A) + wb * A / J + A * A * A / (3.0 * J * J);
    m.dx_dw1 = wb / A + A / J;
    m.dx_dw0 = t1 - wa / A;  // b0 = 0: dx1/dw0 = t1, d(-wa^2/2A)/dw0 = -wa/A
    return m;
  }
  const double ap = std::max(std::sqrt(std::max(0.0, J * dv + b0 * b0 / 2.0)), std::max(b0, 0.0));
  const double t1 = (ap - b0) / J;
  const double x1 = t1 * (w0 + t1 * (b0 / 2.0 + t1 * J / 6.0));
  const double wa = w0 + (ap * ap - b0 * b0) / (2.0 * J);
  m.x = x1 + wa * ap / J + ap * ap * ap / (3.0 * J * J);
  // dx/dap = 2 wa/J + 2 ap^2/J^2; dap/dw1 = J/(2 ap); for b0 = 0 the w0 slope also has
  // dap/dw0 = -J/(2 ap) and the explicit terms t1 + ap/J.
  const double dx_dap = 2.0 * wa / J + 2.0 * ap * ap / (J * J);
  m.dx_dw1 = ap > 0.0 ? dx_dap * J / (2.0 * ap) : inf;
  m.dx_dw0 = ap > 0.0 ? t1 + ap / J - dx_dap * J / (2.0 * ap) : -inf;
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
  const double v_stop = v0 + a0 * std::fabs(a0) / (2.0 * J);
  if (std::fabs(v1 - v_stop) <= 1e-15 * std::max({1.0, std::fabs(v0), std::fabs(v1)})) {
    // As plan_ramp: only a0 is zeroed (no sub-femto velocity ramp), so the distance used to
    // size the cruise is the one the appended ramp covers.
    const double t = std::fabs(a0) / J, j = a0 > 0 ? -J : J;
    return {t * (v0 + t * (a0 / 2.0 + t * j / 6.0)), inf};
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
