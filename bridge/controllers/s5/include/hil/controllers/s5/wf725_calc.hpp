// SPDX-License-Identifier: MIT
#pragma once
// WF 725/726 machine-data calculators (manual §4.3, digest wf725-726.md §3.5): what a user
// computes when setting up an axis, with the MD each figure goes into. Pure.
//   encoder selection  incremental I_GE = S / (4 i_GS A), absolute I_GE = S_G / A
//   MD 19/20           B_I = S / (I_G MD21 i_GS A) (incremental), S_G / (I_G A) (absolute);
//                      MD 19 = integer part (0..9), MD 20 = 8 fraction digits (rounded)
//   MD 34 (I)          4 x encoder lines (pulses per revolution for the checks 08/09)
//   MD 3               n i_GM A I_G B_I MD21 / 10 (absolute: without MD21), 10^-2 mm/min, rounded down
//   MD 1/MD 2          MD3[mm/min] / (60 t[s]) mm/s^2
//   DAC (MD 23)        s_max = v_max / K_v; DAC_max = MD23 2047 / 10 000 mV; factor = DAC_max / s_max;
//                      Factor_DAC = 2047 MD23 MD22 A / (10 000 MD3[mm/min]) < 3
//   MD 24 / MD 26      MD 24 = 1.2 v_max / K_v, MD 26 = 0.1 s_max; s_Limit = 1.5 v / v_max MD24 in
//                      [MD 26, MD 24]: MD 26 below v = MD26 v_max / (1.5 MD24), MD 24 above v_max / 1.5
//   MD 34 (A) minimum  5 t_z[ms] v_max / (60 B_I A) steps (t_z 4 ms WF 725, 6/8 ms WF 726)
//   MD 7 (A_P)         (possible steps - used steps) / 2
//   MD 33, MD 35       3 x / - the standstill following error
//   open loop (AK)     MD 1/MD 2 = G_soll 100 / t [mV/s]; speed of a level = G 100 mV / 10 V x the drive's
//                      speed at 10 V; braking distance from the last level MD 44 on the MD 2 ramp (or the
//                      drive's own) -> MD 48 = braking distance + half a cycle's travel, spread +- that

#include <optional>
#include <string>
#include <vector>

namespace hil::controllers::s5 {

struct Wf725CalcInput {
  int series = 726;                        ///< 725 or 726 (cycle time t_z for MD 34 (A))
  bool jerk_limit = false;                 ///< WF 726 with MD 38/39: 8 ms cycle
  std::optional<int> resolution_um{};      ///< A: 1, 10, 100 (MD 49)
  bool absolute = false;                   ///< absolute encoder (MD 4 = 2/4)
  std::optional<double> pitch_um{};        ///< S: spindle pitch (µm) or rotary increments per revolution
  std::optional<double> range_um{};        ///< S_G: absolute encoder, traversing range (µm)
  std::optional<double> ratio{};           ///< i_GS spindle : encoder (default 1)
  std::optional<double> encoder_pulses{};  ///< I_G: lines per revolution (incremental) / total steps (absolute)
  std::optional<double> factor{};          ///< B_I given directly (MD 19 + MD 20 10^-8), instead of S and I_G
  std::optional<int> multiplication{};     ///< MD 21: 1, 2, 4 (incremental; default 4)
  bool rotary = false;                     ///< S is one revolution of a rotary axis (MD 18 = S)
  std::optional<double> motor_rpm{};       ///< n: maximum motor speed
  std::optional<double> motor_ratio{};     ///< i_GM motor : encoder speed ratio (default 1)
  std::optional<double> vmax_mm_min{};     ///< maximum feed (instead of n)
  std::optional<double> ramp_s{};          ///< time to reach the maximum feed -> MD 1/MD 2
  std::optional<double> kv{};              ///< K_v (m/min)/mm (MD 22)
  std::optional<double> dac_mv{};          ///< MD 23 (default 8000 mV)
  std::optional<double> md24_um{};         ///< given MD 24 (else 1.2 v_max / K_v)
  std::optional<double> md26_um{};         ///< given MD 26 (else 0.1 s_max)
  std::optional<double> feed_mm_min{};     ///< a programmed feed: its following-error limit s_Limit
  std::optional<double> used_steps{};      ///< MD 7 (A_P): steps used of `possible_steps`
  std::optional<double> possible_steps{};  ///< MD 7 (A_P): steps the encoder has
  std::optional<double> standstill_um{};   ///< measured standstill following error -> MD 33, MD 35
  // open loop (MD 4 = 3/4)
  std::optional<int> level{};                  ///< G_soll: the speed level the ramp MD 1 reaches in ramp_s
  std::optional<double> drive_speed_mm_min{};  ///< the drive's speed at 10 V (level 100)
  std::optional<int> creep_level{};            ///< MD 44: the last speed level before speed 0
  std::optional<double> md2_mv_s{};            ///< MD 2 (WF 726), mV/s; 0 = step change
  std::optional<double> drive_acceleration{};  ///< the drive's own acceleration, mm/s^2 (a step of the voltage)
};

struct Wf725CalcLine {
  std::string quantity{};
  double value = 0.0;
  std::string unit{};
  std::string md{};  ///< which MD to enter it in, or "" (derived only)
};

struct Wf725CalcResult {
  std::vector<Wf725CalcLine> lines{};
  std::vector<std::string> problems{};  ///< violated MD rules, with the MD and the module's error number
  [[nodiscard]] std::optional<double> get(const std::string& quantity) const;
};

[[nodiscard]] Wf725CalcResult wf725_calculate(const Wf725CalcInput& in);

}  // namespace hil::controllers::s5
