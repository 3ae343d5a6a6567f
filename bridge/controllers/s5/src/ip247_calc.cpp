// SPDX-License-Identifier: MIT
#include "hil/controllers/s5/ip247_calc.hpp"

#include <cmath>

namespace hil::controllers::s5 {

std::optional<double> Ip247CalcResult::get(const std::string& quantity) const {
  for (const auto& l : lines) {
    if (l.quantity == quantity) return l.value;
  }
  return std::nullopt;
}

Ip247CalcResult ip247_calculate(const Ip247CalcInput& in) {
  Ip247CalcResult r;
  const auto add = [&r](std::string q, double v, std::string unit, std::string md = "") {
    r.lines.push_back({std::move(q), v, std::move(unit), std::move(md)});
  };
  std::optional<double> ppr;
  if (in.pulses_per_rev) ppr = *in.pulses_per_rev;
  if (in.step_angle_deg && *in.step_angle_deg > 0) ppr = 360.0 / *in.step_angle_deg * (in.half_step ? 2.0 : 1.0);
  if (ppr) {
    add("pulses_per_rev", *ppr, "pulses/rev", "DW n+14");
    if (*ppr < 12 || *ppr > 1000 || std::fabs(*ppr - std::round(*ppr)) > 1e-9) {
      r.problems.push_back("pulses/rev must be an integer 12..1000 (MD error 5)");
    }
  }
  std::optional<double> res;
  if (ppr && in.gear_um_per_rev) {
    add("gear", *in.gear_um_per_rev, "BU/rev", "DD n+15");
    res = *in.gear_um_per_rev / *ppr;  // §2.5.3.4
    add("resolution", *res, "BU/pulse");
    if (*res < 1.0) r.problems.push_back("resolution below 1 BU/pulse (MD error 9)");
  }
  std::optional<double> fmax = in.fmax_hz;
  if (res && in.speed_per_min) {
    const double f = *in.speed_per_min * 1000.0 / 60.0 / *res;  // f = v[unit/s] * ppr / gear
    add("frequency", f, "Hz");
    if (!fmax) fmax = f;
    if (fmax && f > *fmax + 1e-9) r.problems.push_back("the speed needs more than fmax (MD error 4)");
  }
  if (fmax) {
    add("fmax", *fmax, "Hz", "DD n+5");
    if (*fmax < 40 || *fmax > 100'000) r.problems.push_back("fmax outside 40 Hz..100 kHz (MD error 3)");
    // Pulse width: 1..31 µs and at most half the period of fmax (§2.5.1.2).
    add("pulse_width_max", std::min(31.0, std::floor(0.5e6 / *fmax)), "us", "DW n+11");
    if (res) {
      add("vmax", *fmax * *res * 60.0 / 1000.0, "unit/min");
      add("vmin_at_1Hz", 1.0 * *res * 60.0 / 1000.0, "unit/min");
    }
  }
  if (fmax && in.fss_hz && in.accel_hz_per_ms) {
    const double fss = *in.fss_hz;
    const double big_f = (*fmax - fss) / 0.95;  // §2.5.3.7
    const double tau_ms = big_f / *in.accel_hz_per_ms;
    add("F", big_f, "Hz");
    add("tau", tau_ms, "ms");
    add("t_b", 3.0 * tau_ms, "ms");
    if (tau_ms < 5.0 || tau_ms > 2600.0) r.problems.push_back("tau outside 5..2600 ms (MD error 6)");
    if (fss >= *fmax) r.problems.push_back("fss must be below fmax (MD error 16)");
    // Braking distance from fmax (t_v = 3 tau): s = F (t + tau (e^(-t/tau) - 1)) + fss t.
    const double tau_s = tau_ms / 1000.0, t = 3.0 * tau_s;
    const double steps = big_f * (t + tau_s * (std::exp(-t / tau_s) - 1.0)) + fss * t;
    add("braking_distance", std::round(steps), "pulses");
    if (res) add("braking_distance_bu", std::round(steps) * *res, "BU");
  }
  if (res && ppr && in.range_bu) {
    const double per_rev = *ppr * *res;
    const double k = *in.range_bu / per_rev;
    add("range_revolutions", k, "rev");
    const bool reproducible = std::fabs(k - std::round(k)) < 1e-9;
    add("reference_reproducible", reproducible ? 1.0 : 0.0, "");
    const double steps = *in.range_bu / *res;
    if (std::fabs(steps - std::round(steps)) > 1e-9) {
      r.problems.push_back("rotary range is not an integer multiple of the resolution");
    }
  }
  return r;
}

}  // namespace hil::controllers::s5
