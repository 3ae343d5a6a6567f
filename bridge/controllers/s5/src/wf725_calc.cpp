// SPDX-License-Identifier: MIT
// WF 725/726 machine-data calculators (manual §4.3 MD 1, 3, 7, 19-21, 23, 24, 26, 33, 34, 35).
#include "hil/controllers/s5/wf725_calc.hpp"
#include "hil/controllers/s5/wf725_open_loop.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace hil::controllers::s5 {

std::optional<double> Wf725CalcResult::get(const std::string& quantity) const {
  for (const auto& l : lines)
    if (l.quantity == quantity) return l.value;
  return std::nullopt;
}

Wf725CalcResult wf725_calculate(const Wf725CalcInput& in) {
  Wf725CalcResult r;
  const auto add = [&r](std::string q, double v, std::string unit, std::string md = "") {
    r.lines.push_back({std::move(q), v, std::move(unit), std::move(md)});
  };
  const auto problem = [&r](std::string p) { r.problems.push_back(std::move(p)); };
  const double ratio = in.ratio.value_or(1.0);
  const int mult = in.multiplication.value_or(4);
  double a = 0.0;  // resolution in um, 0 = not given
  if (in.resolution_um) {
    a = *in.resolution_um;
    const int md49 = *in.resolution_um == 1 ? 1 : *in.resolution_um == 10 ? 2 : *in.resolution_um == 100 ? 3 : 0;
    if (md49 == 0) {
      problem(fmt::format("resolution {} um: the WF has 1, 10 or 100 um (MD 49 = 1, 2, 3)", *in.resolution_um));
      a = 0.0;
    } else {
      add("resolution", a, "um", "MD 49 = " + std::to_string(md49));
    }
  }
  if (!in.absolute && mult != 1 && mult != 2 && mult != 4) problem(fmt::format("MD 21 = {}: 1, 2 or 4", mult));
  if (ratio <= 0) problem("the spindle:encoder ratio must be > 0");

  // Encoder selection and the pulse evaluation factor MD 19/20 (§4.3 MD 21 examples a1, a2, b).
  std::optional<double> bi;
  const std::optional<double> travel = in.absolute ? in.range_um : in.pitch_um;
  if (a > 0 && travel && ratio > 0) {
    const double ige = in.absolute ? *travel / a : *travel / (4.0 * ratio * a);
    add("encoder_pulses_needed", ige, in.absolute ? "steps" : "pulses/rev");
    if (in.encoder_pulses && *in.encoder_pulses > 0) {
      bi = in.absolute ? *travel / (*in.encoder_pulses * a) : *travel / (*in.encoder_pulses * mult * ratio * a);
      add("B_I", *bi, "");
      const double md19 = std::floor(*bi);
      double md20 = std::round((*bi - md19) * 1e8);
      double md19_out = md19;
      if (md20 >= 1e8) {  // rounding carried into the integer part
        md20 -= 1e8;
        md19_out += 1;
      }
      add("MD19", md19_out, "", "MD 19");
      add("MD20", md20, "", "MD 20");
      if (md19_out > 9) problem(fmt::format("B_I = {:.8f}: MD 19 takes 0..9 (choose a finer encoder)", *bi));
      if (md19_out == 0 && md20 == 0) problem("B_I rounds to 0: MD 19 = MD 20 = 0 gives error 19");
      if (!in.absolute) {
        add("MD21", mult, "", "MD 21");
        const double md34 = 4.0 * *in.encoder_pulses;
        add("MD34", md34, "pulses/rev", "MD 34");
        if (md34 < 100) problem("MD 34 (pulses per revolution) must be >= 100 (error 1A at 0)");
      }
      if (in.rotary) add("MD18", *travel, "10^-3 deg", "MD 18");
    }
  }

  if (!bi && in.factor && *in.factor > 0) {
    bi = *in.factor;
    add("B_I", *bi, "");
  }

  // MD 3 from the motor speed (§4.3 MD 3), rounded down so that the following-error supervision holds.
  std::optional<double> vmax = in.vmax_mm_min;
  if (!vmax && in.motor_rpm && a > 0 && bi && in.encoder_pulses) {
    const double md3 = std::floor(*in.motor_rpm * in.motor_ratio.value_or(1.0) * a * *in.encoder_pulses * *bi *
                                      (in.absolute ? 1.0 : mult) / 10.0 +
                                  1e-6);
    add("MD3", md3, "10^-2 mm/min", "MD 3");
    vmax = md3 / 100.0;
  } else if (vmax) {
    add("MD3", std::floor(*vmax * 100.0 + 1e-6), "10^-2 mm/min", "MD 3");
  }
  if (vmax) {
    add("vmax", *vmax, "mm/min");
    const double md3 = std::floor(*vmax * 100.0 + 1e-6);
    const double hi = (a > 1) ? 30'000'000 : 3'000'000;
    if (md3 < 10 || md3 > hi) problem(fmt::format("MD 3 = {:.0f}: 10..{:.0f} (error 20)", md3, hi));
  }
  if (vmax && in.ramp_s && *in.ramp_s > 0) {
    const double md1 = *vmax / (60.0 * *in.ramp_s);
    add("MD1", md1, "mm/s^2", "MD 1 / MD 2");
    if (md1 < 1) problem("MD 1/MD 2 below 1 mm/s^2: MD 2 = 0 gives error 71");
  }

  // DAC scaling (§4.3 MD 23) and the dynamic following-error window (MD 24/26).
  std::optional<double> smax;
  if (vmax && in.kv && *in.kv > 0) {
    add("MD22", *in.kv, "(m/min)/mm", "MD 22");
    if (*in.kv < 0.2 || *in.kv > 9.0) problem("MD 22 (K_v) takes 0.20..9.00 (m/min)/mm");
    smax = *vmax / *in.kv;  // (m/min)/mm = (mm/min)/um
    add("s_max", *smax, "um");
    const double u = in.dac_mv.value_or(8000.0);
    add("MD23", u, "mV", "MD 23");
    if (u < 1000 || u > 10'000) problem("MD 23 takes 1000..10000 mV");
    const double dac_max = std::round(u * 2047.0 / 10'000.0);
    add("DAC_max", dac_max, "increments");
    const double factor = dac_max / *smax;
    add("factor_DAC_per_um", factor, "1/um");
    if (a > 0) {
      const double f = 2047.0 * u * *in.kv * a / (10'000.0 * *vmax);
      add("Factor_DAC", f, "", "data code 29 reads it");
      if (f >= 3) problem(fmt::format("Factor_DAC = {:.4f} must be < 3: raise MD 3 or lower MD 22/MD 23", f));
    }
    if (factor > 0) add("following_error_per_DAC_step", std::ceil(1.0 / factor), "increments");
    const double md24 = in.md24_um.value_or(std::round(1.2 * *smax));
    const double md26 = in.md26_um.value_or(std::round(0.1 * *smax));
    if (!in.md24_um) add("MD24", md24, "um", "MD 24");
    if (!in.md26_um) add("MD26", md26, "um", "MD 26");
  }
  if (vmax && (in.md24_um || smax)) {
    const double md24 = in.md24_um.value_or(smax ? std::round(1.2 * *smax) : 0.0);
    const double md26 = in.md26_um.value_or(smax ? std::round(0.1 * *smax) : 0.0);
    if (md24 > 0) {
      add("MD26_applies_below", md26 * *vmax / (1.5 * md24), "mm/min");
      add("MD24_applies_above", *vmax / 1.5, "mm/min");
      if (md26 > md24) problem("MD 26 must not exceed MD 24");
      if (in.feed_mm_min) {
        const double lim = std::clamp(1.5 * *in.feed_mm_min / *vmax * md24, md26, md24);
        add("s_Limit", lim, "um");
      }
    }
  }

  // Absolute encoders: the minimum travel difference MD 34 (§4.3 MD 34 (A)).
  if (in.absolute && vmax && a > 0 && bi) {
    const double tz = in.series == 725 ? 4.0 : (in.jerk_limit ? 8.0 : 6.0);
    add("cycle", tz, "ms");
    add("MD34_minimum", 5.0 * tz * *vmax / (60.0 * *bi * a), "steps", "MD 34 (more than this)");
  }
  if (in.possible_steps && in.used_steps) {
    const double md7 = (*in.possible_steps - *in.used_steps) / 2.0;
    add("MD7", md7, "steps", "MD 7");
    if (md7 < 0) problem("MD 7: more steps used than the encoder has");
  }
  if (in.standstill_um) {
    add("MD33", 3.0 * *in.standstill_um, "um", "MD 33");
    add("MD35", -*in.standstill_um, "um", "MD 35");
    if (std::fabs(*in.standstill_um) > 255.0 * in.resolution_um.value_or(1))
      problem("MD 35 is limited to +-255 resolution steps");
  }
  // Open loop (§4.3 MD 1/2 AK, MD 42-48).
  if (in.level && in.ramp_s && *in.ramp_s > 0) {
    const double md1 = *in.level * 100.0 / *in.ramp_s;
    add("MD1_open_loop", md1, "mV/s", "MD 1 / MD 2 (open loop, WF 726)");
    if (*in.level < 1 || *in.level > 99) problem("speed levels are 1..99 (MD 42-44)");
    if (md1 > 65535) problem(fmt::format("MD 1 = {:.0f} mV/s: at most 65 535", md1));
    if (in.series == 725) problem("the open-loop voltage ramps MD 1/MD 2 exist on the WF 726 only");
  }
  if (in.drive_speed_mm_min && *in.drive_speed_mm_min > 0) {
    const Wf725OpenLoopDrive d{*in.drive_speed_mm_min, in.drive_acceleration.value_or(0.0)};
    if (in.level) add("v_level", wf725_level_velocity(d, *in.level) * 60.0, "mm/min");
    if (in.creep_level) {
      const double v = wf725_level_velocity(d, *in.creep_level);  // mm/s
      const double ramp = in.md2_mv_s.value_or(0.0) * d.speed_at_10v_mm_min / 60.0 / 10000.0;
      const double acc = in.drive_acceleration ? wf725_ramp_acceleration(d, in.md2_mv_s.value_or(0.0)) : ramp;
      add("v_creep", v * 60.0, "mm/min");
      const double tz = in.series == 725 ? 4.0 : (in.jerk_limit ? 8.0 : 6.0);
      if (acc > 0) {
        const double brake = v * v / (2.0 * acc) * 1000.0;
        const double spread = v * tz / 2.0;  // µm: half a cycle's travel (v mm/s x tz ms / 2)
        add("brake_creep", brake, "um");
        add("MD48", std::ceil(brake + spread), "um", "MD 48");
        add("stop_spread", spread, "um", "MD 33 at least");
      } else {
        problem("MD 2 = 0 (step change) needs --drive-acceleration: the braking distance is the drive's");
      }
    }
  }
  return r;
}

}  // namespace hil::controllers::s5
