// SPDX-License-Identifier: MIT
// WF 725/726 machine-data calculator against every calculation of the manual (§4.3; digest
// wf725-726.md §3.5: MD 1, MD 3, MD 7, MD 19/20/21 examples a1/a2/b, MD 23 DAC scaling, MD 24/26
// crossover, MD 34 (A) minimum), as numbers and as the figures `hilbridge profile calc wf725-726` prints.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

#include "hil/controllers/s5/wf725_calc.hpp"

using namespace hil::controllers::s5;

TEST(Wf725Calc, EncoderAndPulseEvaluationFactor) {
  // a1: 1 um, spindle 10 mm, 1:1 -> 2500 pulses/rev; B_I 1.0: MD 19 = 1, MD 20 = 0, MD 21 = 4.
  auto r = wf725_calculate({.resolution_um = 1, .pitch_um = 10'000, .encoder_pulses = 2500});
  EXPECT_DOUBLE_EQ(*r.get("encoder_pulses_needed"), 2500.0);
  EXPECT_DOUBLE_EQ(*r.get("B_I"), 1.0);
  EXPECT_EQ(*r.get("MD19"), 1.0);
  EXPECT_EQ(*r.get("MD20"), 0.0);
  EXPECT_EQ(*r.get("MD21"), 4.0);
  EXPECT_EQ(*r.get("MD34"), 10'000.0);  // 4 x lines, the MD 34 example
  EXPECT_TRUE(r.problems.empty());
  // a2: 10 um, rotary 360.000 degrees, 2.51:1 -> 3585.657; 5000 lines: B_I 0.717131474,
  // MD 19 = 0, MD 20 = 71 713 147, MD 18 = 360 000.
  r = wf725_calculate(
      {.resolution_um = 10, .pitch_um = 360'000, .ratio = 2.51, .encoder_pulses = 5000, .rotary = true});
  EXPECT_NEAR(*r.get("encoder_pulses_needed"), 3585.657, 0.0005);
  EXPECT_NEAR(*r.get("B_I"), 0.717131474, 1e-9);
  EXPECT_EQ(*r.get("MD19"), 0.0);
  EXPECT_EQ(*r.get("MD20"), 71'713'147.0);
  EXPECT_EQ(*r.get("MD18"), 360'000.0);
  // b: absolute, 100 um, 25 m -> 250 000 steps; 512 x 512: B_I 0.95367432, MD 20 = 95 367 432.
  r = wf725_calculate({.resolution_um = 100, .absolute = true, .range_um = 25'000'000, .encoder_pulses = 262'144});
  EXPECT_DOUBLE_EQ(*r.get("encoder_pulses_needed"), 250'000.0);
  EXPECT_EQ(*r.get("MD19"), 0.0);
  EXPECT_EQ(*r.get("MD20"), 95'367'432.0);
  // B_I >= 10 does not fit MD 19 (0..9).
  EXPECT_FALSE(wf725_calculate({.resolution_um = 1, .pitch_um = 100'000, .encoder_pulses = 100}).problems.empty());
}

TEST(Wf725Calc, OpenLoopRampAndLastTravelDifference) {
  // §4.3 MD 1 (AK): MD 1 = G_soll 100 / t: level 60 in 5 s -> 1200 mV/s (the manual's example value).
  auto r = wf725_calculate({.ramp_s = 5, .level = 60});
  EXPECT_DOUBLE_EQ(*r.get("MD1_open_loop"), 1200.0);
  EXPECT_TRUE(r.problems.empty());
  r = wf725_calculate({.series = 725, .ramp_s = 5, .level = 60});
  EXPECT_FALSE(r.problems.empty()) << "no voltage ramps on the WF 725";
  r = wf725_calculate({.ramp_s = 0.01, .level = 99});
  EXPECT_FALSE(r.problems.empty()) << "990 000 mV/s is beyond 65 535";
  // Creep level 5 on a 10 m/min-at-10 V drive: 500 mm/min = 8.33 mm/s; MD 2 = 0 with the drive's
  // 1000 mm/s^2: 34.7 um braking; half a 6 ms WF 726 cycle of travel 25 um -> MD 48 = 60 um.
  r = wf725_calculate({.drive_speed_mm_min = 10000, .creep_level = 5, .md2_mv_s = 0, .drive_acceleration = 1000});
  EXPECT_DOUBLE_EQ(*r.get("v_creep"), 500.0);
  EXPECT_NEAR(*r.get("brake_creep"), 34.722, 1e-3);
  EXPECT_NEAR(*r.get("stop_spread"), 25.0, 1e-9);
  EXPECT_EQ(*r.get("MD48"), 60.0);
  // MD 2 = 600 mV/s: 10 mm/s^2 -> 3472 um braking from level 5.
  r = wf725_calculate({.drive_speed_mm_min = 10000, .creep_level = 5, .md2_mv_s = 600});
  EXPECT_NEAR(*r.get("brake_creep"), 3472.2, 0.1);
  r = wf725_calculate({.drive_speed_mm_min = 10000, .creep_level = 5, .md2_mv_s = 0});
  EXPECT_FALSE(r.problems.empty()) << "a step change needs the drive's acceleration";
}

TEST(Wf725Calc, FeedRampsDacAndWindows) {
  // MD 3: n 3000/min, 10 um, 2500 pulses, 1:1, B_I 1.0, x4 -> 30 000 000 (300 m/min).
  auto r = wf725_calculate({.resolution_um = 10, .pitch_um = 100'000, .encoder_pulses = 2500, .motor_rpm = 3000});
  EXPECT_EQ(*r.get("MD3"), 30'000'000.0);
  // MD 1/MD 2: 30 000 mm/min in 10 s -> 50 mm/s^2.
  r = wf725_calculate({.vmax_mm_min = 30'000, .ramp_s = 10});
  EXPECT_DOUBLE_EQ(*r.get("MD1"), 50.0);
  // MD 23: 10 m/min, 8 V, K_v 1.00 -> s 10 000 um, DAC_max 1638, factor 0.1638 / um, < 3; MD 3 = 1 000 000.
  r = wf725_calculate({.resolution_um = 1, .vmax_mm_min = 10'000, .kv = 1.0, .dac_mv = 8000});
  EXPECT_EQ(*r.get("MD3"), 1'000'000.0);
  EXPECT_DOUBLE_EQ(*r.get("s_max"), 10'000.0);
  EXPECT_DOUBLE_EQ(*r.get("DAC_max"), 1638.0);
  EXPECT_NEAR(*r.get("factor_DAC_per_um"), 0.1638, 1e-12);
  EXPECT_NEAR(*r.get("Factor_DAC"), 0.16376, 1e-9);
  EXPECT_EQ(*r.get("following_error_per_DAC_step"), 7.0);  // "increase the following error by 7 increments"
  EXPECT_EQ(*r.get("MD24"), 12'000.0);                     // 1.2 v_max / K_v
  EXPECT_EQ(*r.get("MD26"), 1'000.0);                      // 0.1 s_max
  EXPECT_TRUE(r.problems.empty());
  // MD 24/26: MD 26 = 100 um, MD 24 = 11 000 um, 10 m/min -> MD 26 below 60.606 mm/min, MD 24 above 6.667 m/min.
  r = wf725_calculate({.vmax_mm_min = 10'000, .md24_um = 11'000, .md26_um = 100, .feed_mm_min = 3000});
  EXPECT_NEAR(*r.get("MD26_applies_below"), 60.606, 0.0005);
  EXPECT_NEAR(*r.get("MD24_applies_above"), 6666.667, 0.0005);
  EXPECT_DOUBLE_EQ(*r.get("s_Limit"), 4950.0);  // 1.5 * 3000 / 10 000 * 11 000
  // Factor_DAC >= 3 breaks the rule.
  EXPECT_FALSE(
      wf725_calculate({.resolution_um = 100, .vmax_mm_min = 1000, .kv = 2.0, .dac_mv = 10'000}).problems.empty());
}

TEST(Wf725Calc, AbsoluteEncoderChecks) {
  // MD 34 (A), WF 725 B: 10 000 mm/min, B_I 2.5, 10 um -> 133 steps in 5 cycles of 4 ms.
  auto r =
      wf725_calculate({.series = 725, .resolution_um = 10, .absolute = true, .factor = 2.5, .vmax_mm_min = 10'000});
  EXPECT_NEAR(*r.get("MD34_minimum"), 133.33, 0.005);
  EXPECT_DOUBLE_EQ(*r.get("cycle"), 4.0);
  // WF 726 with a jerk limit: 8 ms.
  r = wf725_calculate(
      {.jerk_limit = true, .resolution_um = 10, .absolute = true, .factor = 2.5, .vmax_mm_min = 10'000});
  EXPECT_DOUBLE_EQ(*r.get("cycle"), 8.0);
  // MD 7 (A_P): 512 steps of which 360 used -> 76.
  r = wf725_calculate({.used_steps = 360, .possible_steps = 512});
  EXPECT_DOUBLE_EQ(*r.get("MD7"), 76.0);
  // MD 33 / MD 35 from a standstill following error of 4 um.
  r = wf725_calculate({.standstill_um = 4});
  EXPECT_DOUBLE_EQ(*r.get("MD33"), 12.0);
  EXPECT_DOUBLE_EQ(*r.get("MD35"), -4.0);
}

namespace {
std::string hilbridge(const std::string& args, int& status) {
  const std::string cmd = std::string(HIL_HILBRIDGE) + " " + args + " 2>&1";
  std::string out;
  FILE* p = ::popen(cmd.c_str(), "r");
  if (!p) return out;
  std::array<char, 4096> buf{};
  while (std::fgets(buf.data(), static_cast<int>(buf.size()), p)) out += buf.data();
  const int st = ::pclose(p);
  status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  return out;
}
bool has(const std::string& out, const std::string& s) {
  return out.find(s) != std::string::npos;
}
}  // namespace

TEST(Wf725Calc, ProfileCalcCommandPrintsTheManualsFigures) {
  int status = -1;
  auto out = hilbridge("profile calc wf725-726 --resolution 1 --pitch 10000 --pulses 2500", status);
  EXPECT_EQ(status, 0) << out;
  EXPECT_TRUE(has(out, "2500") && has(out, "enter in MD 19") && has(out, "enter in MD 21")) << out;
  out = hilbridge("profile calc wf725-726 --resolution 10 --pitch 360000 --rotary --ratio 2.51 --pulses 5000", status);
  EXPECT_EQ(status, 0) << out;
  EXPECT_TRUE(has(out, "3585.657") && has(out, "0.71713147") && has(out, "71713147") && has(out, "MD 49 = 2") &&
              has(out, "enter in MD 18"))
      << out;
  out = hilbridge("profile calc wf725-726 --resolution 100 --absolute --range 25000000 --pulses 262144", status);
  EXPECT_EQ(status, 0) << out;
  EXPECT_TRUE(has(out, "250000") && has(out, "95367432")) << out;
  out = hilbridge("profile calc wf725-726 --resolution 10 --pitch 100000 --pulses 2500 --motor-speed 3000", status);
  EXPECT_TRUE(has(out, "30000000")) << out;
  out = hilbridge("profile calc wf725-726 --vmax 30000 --ramp-time 10", status);
  EXPECT_TRUE(has(out, "MD1") && has(out, " 50 ") && has(out, "enter in MD 1 / MD 2")) << out;
  out = hilbridge("profile calc wf725-726 --resolution 1 --vmax 10000 --kv 1 --dac 8000", status);
  EXPECT_EQ(status, 0) << out;
  EXPECT_TRUE(has(out, "1000000") && has(out, "1638") && has(out, "0.1638") && has(out, "0.16376") &&
              has(out, "enter in MD 23"))
      << out;
  out = hilbridge(
      "profile calc wf725-726 --level 60 --ramp-time 5 --drive-speed 10000 --creep-level 5 --md2 0 "
      "--drive-acceleration 1000",
      status);
  EXPECT_EQ(status, 0) << out;
  EXPECT_TRUE(has(out, "1200") && has(out, "mV/s") && has(out, "enter in MD 48") && has(out, " 60 ")) << out;
  out = hilbridge("profile calc wf725-726 --vmax 10000 --md24 11000 --md26 100", status);
  EXPECT_TRUE(has(out, "60.606") && has(out, "6666.66")) << out;
  out = hilbridge("profile calc wf725-726 --module WF725 --absolute --resolution 10 --factor 2.5 --vmax 10000", status);
  EXPECT_TRUE(has(out, "133.33") && has(out, "MD 34")) << out;
  out = hilbridge("profile calc wf725-726 --possible-steps 512 --used-steps 360 --json", status);
  EXPECT_EQ(status, 0) << out;
  EXPECT_TRUE(has(out, "\"MD7\"") && has(out, "76")) << out;
  out = hilbridge("profile calc wf725-726 --resolution 1 --pitch 100000 --pulses 100", status);
  EXPECT_EQ(status, 1) << out;
  EXPECT_TRUE(has(out, "MD 19 takes 0..9")) << out;
  out = hilbridge("profile calc wf725-726", status);
  EXPECT_EQ(status, 2) << out;
  EXPECT_TRUE(has(out, "nothing to compute")) << out;
}
