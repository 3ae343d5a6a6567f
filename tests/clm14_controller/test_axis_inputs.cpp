// SPDX-License-Identifier: MIT
// CLM1.4 per-axis input functions (manual §7.3, §7.4, §8.2; digest §5.4, §5.6, §5.13): the B017
// override inputs (binary, Gray code), Ax15 feed angle and interrupt, Ax30 open feed roll, Ax32.
#include <gtest/gtest.h>

#include "rig.hpp"

namespace hil::controllers::clm14::testing {
namespace {

using namespace std::chrono_literals;

/// The set-point velocity of axis 1 (IU/s).
double command_velocity(const Rig& r) {
  return r.motion_axes[0]->status().command_velocity;
}

/// Run a long POI at 999 ‰ (99.9 IU/s) and return its cruise velocity after 1.5 s.
double cruise(Rig& r) {
  r.program({{0, "POI 1 +000500.000 999"}, {1, "JMP 0001"}});  // (JST would stop the feed)
  r.start_auto();
  r.run_for(1500ms);
  EXPECT_EQ(r.clm.error(), 0) << r.clm.error_message();
  return command_velocity(r);
}

TEST(ClmOverrideInputs, BinaryOnI101ScalesBySumOver255) {
  Rig r({{"B017", "0 5 0 0 0 0"}});
  r.clm.image().set_byte(byte("I1.01"), 128);
  EXPECT_NEAR(cruise(r), 99.9 * 128.0 / 255.0, 1e-6);  // vector 17: Vo = Vp × s / 255
}

TEST(ClmOverrideInputs, GrayCodeTable) {
  // (I1.01.4, .5, .6, .7) -> %: 1000 1, 1100 2, 0110 6, 1010 10, 0011 30, 1111 50, 0101 70, 1001 90, 0001 100
  const std::array<std::pair<std::uint8_t, int>, 9> table{
      {{0x10, 1}, {0x30, 2}, {0x60, 6}, {0x50, 10}, {0xC0, 30}, {0xF0, 50}, {0xA0, 70}, {0x90, 90}, {0x80, 100}}};
  for (const auto& [code, percent] : table) {
    Rig r({{"B017", "0 6 0 0 0 0"}});
    r.clm.image().set_byte(byte("I1.01"), static_cast<std::uint8_t>(code | 0x0F));  // bits 0-3 ignored
    EXPECT_NEAR(cruise(r), 99.9 * percent / 100.0, 1e-6) << "code " << int{code};
  }
}

TEST(ClmOverrideInputs, ZeroStopsTheFeedWhichResumesToItsTarget) {
  Rig r({{"B017", "0 6 0 0 0 0"}});
  r.clm.image().set_byte(byte("I1.01"), 0x80);  // 100 %
  r.program({{0, "PSI 1 +000100.000 999"}, {1, "SET V600 = V100"}, {2, "JST 0002"}});
  r.start_auto();
  r.run_for(500ms);
  r.clm.image().set_byte(byte("I1.01"), 0x00);  // 0 %
  r.run_for(1s);
  const double held = r.pos();
  EXPECT_LT(held, 90.0);
  EXPECT_NEAR(command_velocity(r), 0.0, 1e-9);
  EXPECT_EQ(r.clm.task(1).pc, 0) << "the PSI waits";
  r.clm.image().set_byte(byte("I1.01"), 0xF0);  // 50 %
  ASSERT_TRUE(r.run_until([&] { return r.clm.task(1).pc == 2; }, 10s));
  EXPECT_NEAR(to_double(r.clm.variable(600)), 100.0, 0.011);
}

TEST(ClmOverrideInputs, VeoHasPriorityAndHomingIsNotOverridden) {
  Rig r({{"B017", "0 5 0 0 0 0"}});
  r.clm.image().set_byte(byte("I1.01"), 51);  // 20 %
  r.program({{0, "VEO 1 4 1 500 0"}, {1, "POI 1 +000500.000 999"}, {2, "JMP 0002"}});
  r.start_auto();
  r.run_for(1500ms);
  EXPECT_NEAR(command_velocity(r), 99.9 * 0.5, 1e-6);
  Rig h({{"B017", "0 5 0 0 0 0"}, {"A124", "M2.01.0 +100 2"}});
  h.clm.image().set_byte(byte("I1.01"), 51);
  h.program({{0, "HOM 1"}, {1, "JMP 0001"}});
  h.start_auto();
  h.run_for(500ms);
  EXPECT_NEAR(command_velocity(h), 10.0, 1e-6) << "V1 = 100 ‰ of Vmax without override";
}

TEST(ClmAnalogAverage, MovingAverageOverTwoToTheCodePlusThreeSamples) {
  AnalogAverage f;
  f.reset(0, 0);
  EXPECT_EQ(f.samples(), 8U);
  for (int k = 1; k <= 8; ++k) {
    f.push(5000);
    EXPECT_EQ(f.millivolts(), 5000.0 * k / 8) << k;  // exact: N is a power of two
  }
  f.push(5000);
  EXPECT_EQ(f.millivolts(), 5000.0);
  f.reset(1, -2000);  // a new code starts from a steady input
  EXPECT_EQ(f.samples(), 16U);
  EXPECT_EQ(f.millivolts(), -2000.0);
  f.reset(8, 0);
  EXPECT_EQ(f.samples(), 2048U);
  f.reset(12, 0);
  EXPECT_EQ(f.code(), 9);
  EXPECT_EQ(f.samples(), 4096U);
  EXPECT_EQ(analog_override(5000.0), 0.5);
  EXPECT_EQ(analog_override(12000.0), 1.0);
  EXPECT_EQ(analog_override(-3000.0), 0.0) << "a negative voltage is 0 % [decided]";
}

TEST(ClmOverrideInputs, AnalogSourceScalesByVoltageOverTenVolts) {
  // §5.6: F = 0 … 1 for 0 … 10 V. Axis 1 on AE1 at 5 V: 50 %; on AE3 at 2.5 V: 25 %.
  Rig r({{"B017", "0 1 0 0 0 0"}});
  r.clm.set_analog_input(1, 5000);
  r.clm.set_analog_input(3, 2500);
  EXPECT_NEAR(cruise(r), 99.9 * 0.5, 1e-6);
  EXPECT_EQ(r.clm.variable(7), to_micro(0.5)) << "V007 normalised to ±1";
  EXPECT_EQ(r.clm.variable(9), to_micro(0.25));
  EXPECT_EQ(r.clm.variable(8), 0);
  Rig q({{"B017", "0 3 0 0 0 0"}});
  q.clm.set_analog_input(3, 2500);
  EXPECT_NEAR(cruise(q), 99.9 * 0.25, 1e-6);
}

TEST(ClmOverrideInputs, AnalogAveragingFollowsAStepOverNCycles) {
  // B017 averaging 1 = 16 samples, one per NC cycle (2 ms): V007 after a 0 -> 10 V step rises by
  // 1/16 per cycle and the feed's override with it.
  Rig r({{"B017", "1 1 0 0 0 0"}});
  r.clm.set_analog_input(1, 0);
  r.program({{0, "POI 1 +000500.000 999"}, {1, "JMP 0001"}});
  r.start_auto();
  r.run_for(200ms);
  EXPECT_EQ(r.clm.variable(7), 0);
  EXPECT_NEAR(command_velocity(r), 0.0, 1e-9) << "0 V: the feed waits";
  EXPECT_NEAR(r.pos(), 0.0, 1e-9);
  r.clm.set_analog_input(1, 10000);
  for (int k = 1; k <= 16; ++k) {
    r.cycle();
    EXPECT_EQ(r.clm.variable(7), to_micro(k / 16.0)) << k;
    EXPECT_EQ(r.clm.analog_average(1), 10000.0 * k / 16) << k;
  }
  r.run_for(1500ms);
  EXPECT_NEAR(command_velocity(r), 99.9, 1e-6);
  r.clm.set_analog_input(1, -5000);  // negative: 0 %, the feed stops with its ramp
  r.run_for(1s);
  EXPECT_NEAR(command_velocity(r), 0.0, 1e-9);
  EXPECT_EQ(r.clm.variable(7), to_micro(-0.5));
  EXPECT_EQ(r.clm.error(), 0);
}

TEST(ClmOverrideInputs, AveragingCodeOutOfRangeIsAParameterError) {
  auto params = base_parameters();
  params["B017"] = "0 7 0 0 0 0";
  auto data = serial::clm14::load_device_data();
  ASSERT_TRUE(data.has_value());
  auto s = make_settings([&](std::string_view n) {
    const auto it = params.find(std::string(n));
    return it != params.end() ? it->second : (*data)->parameter_default(n);
  });
  ASSERT_FALSE(s.has_value());
  EXPECT_EQ(s.error().error, ClmError::parameter_invalid);
  EXPECT_EQ(s.error().message.substr(0, 4), "B017") << s.error().message;
  params["B017"] = "0 4 4 4 4 0";  // the analog sources 1-4 are valid
  EXPECT_TRUE(make_settings([&](std::string_view n) {
                const auto it = params.find(std::string(n));
                return it != params.end() ? it->second : (*data)->parameter_default(n);
              }).has_value());
}

TEST(ClmFeedAngle, NoFeedStartsWithoutItAndLosingItInAFeedIs41) {
  Rig r({{"A115", "I1.02.0 00.00.0"}});
  r.program({{0, "POI 1 +000100.000 999"}, {1, "AKN M2.00.0 1"}, {2, "POI 1 +000100.000 999"}, {3, "JMP 0003"}});
  r.start_auto();
  r.run_for(200ms);
  EXPECT_EQ(r.clm.task(1).pc, 0) << "blocked at the feed line";
  EXPECT_TRUE(r.get(sys::out_inhibit));
  EXPECT_NEAR(r.pos(), 0.0, 1e-9);
  r.set(bit("I1.02.0"), true);
  ASSERT_TRUE(r.run_until([&] { return r.clm.task(1).pc == 2; }, 5s));
  EXPECT_FALSE(r.get(sys::out_inhibit));
  r.run_for(300ms);
  r.set(bit("I1.02.0"), false);
  r.cycle();
  r.cycle();
  EXPECT_EQ(r.clm.error(), 0x41) << r.clm.error_message();
}

TEST(ClmInterrupt, StopsTheMoveRunsOtherLinesAndResumesWithoutStart) {
  Rig r({{"A115", "00.00.0 I1.02.1"}});
  r.set(bit("I1.02.1"), true);
  r.program({{0, "POI 1 +000100.000 999"},
             {1, "SET V601 = +1"},
             {2, "AKN M2.00.0 1"},
             {3, "SET V600 = V100"},
             {4, "JST 0004"}});
  r.start_auto();
  r.run_for(400ms);
  r.set(bit("I1.02.1"), false);
  r.run_for(1s);
  const double stopped = r.pos();
  EXPECT_LT(stopped, 90.0);
  EXPECT_NEAR(command_velocity(r), 0.0, 1e-9);
  EXPECT_EQ(to_double(r.clm.variable(601)), 1.0) << "non-feed lines keep running";
  EXPECT_TRUE(r.get(sys::out_inhibit));
  r.set(bit("I1.02.1"), true);
  ASSERT_TRUE(r.run_until([&] { return r.clm.task(1).pc == 4; }, 5s));
  EXPECT_NEAR(to_double(r.clm.variable(600)), 100.0, 0.011);
  EXPECT_EQ(r.clm.error(), 0);
}

TEST(ClmOpenFeedRoll, CommandZeroInPositionAndFeedsWait) {
  Rig r({{"A130", "I1.02.2 Q1.00.5"}});
  r.program({{0, "PSI 1 +000010.000 999"}, {1, "WAI 00.500"}, {2, "PSI 1 +000010.000 999"}, {3, "JST 0003"}});
  r.start_auto();
  r.run_for(100ms);
  r.set(bit("I1.02.2"), true);  // during the first feed: opens once in position
  EXPECT_FALSE(r.get(bit("Q1.00.5")));
  r.run_for(600ms);
  EXPECT_TRUE(r.get(bit("Q1.00.5")));
  EXPECT_EQ(r.motion_axes[0]->status().state, motion::AxisState::disabled) << "command 0: no position control";
  EXPECT_EQ(r.clm.task(1).pc, 2) << "the next feed waits";
  r.set(bit("I1.02.2"), false);
  ASSERT_TRUE(r.run_until([&] { return r.clm.task(1).pc == 3; }, 5s));
  EXPECT_FALSE(r.get(bit("Q1.00.5")));
  EXPECT_NEAR(r.pos(), 20.0, 0.011);
}

TEST(ClmAx32, VelocityReachedAndDecelerationOutputs) {
  Rig r({{"A132", "Q1.00.6 Q1.00.7"}});
  r.program({{0, "POI 1 +000100.000 999"}, {1, "JMP 0001"}});
  r.start_auto();
  r.run_for(50ms);  // accelerating: 1000 IU/s² for 0.1 s
  EXPECT_FALSE(r.get(bit("Q1.00.6")));
  EXPECT_FALSE(r.get(bit("Q1.00.7")));
  r.run_for(500ms);  // cruising
  EXPECT_TRUE(r.get(bit("Q1.00.6")));
  EXPECT_FALSE(r.get(bit("Q1.00.7")));
  ASSERT_TRUE(r.run_until([&] { return r.get(bit("Q1.00.7")); }, 2s));
  EXPECT_FALSE(r.get(bit("Q1.00.6")));
  EXPECT_NEAR(r.pos(), 100.0 - 99.9 * 99.9 / 2000.0, 0.5) << "braking starts 5 IU before the target";
  r.run_for(500ms);
  EXPECT_FALSE(r.get(bit("Q1.00.6")));
  EXPECT_FALSE(r.get(bit("Q1.00.7")));
}

}  // namespace
}  // namespace hil::controllers::clm14::testing
