// SPDX-License-Identifier: MIT
#include <gtest/gtest.h>

#include "hil/config/yaml_config.hpp"
#include "hil/mocks/sim_drive.hpp"

using namespace std::chrono_literals;
using hil::DriveRequest;
using hil::DriveState;

namespace {

struct Rig {
  hil::mocks::SimDrive drive;
  hil::TimePoint now{};
  explicit Rig(hil::mocks::SimDriveConfig c = {}) : drive(std::move(c)) {}
  void cycle(const hil::DriveCommand& cmd = {}) {
    hil::CycleTime t{now, 1ms};
    drive.read(t);
    drive.write(t, cmd);
    now += 1ms;
  }
  void cycles(int n, const hil::DriveCommand& cmd = {}) {
    for (int i = 0; i < n; ++i) cycle(cmd);
  }
};

}  // namespace

TEST(SimDrive, EnableWalksThePowerStates) {
  Rig rig;
  rig.cycle();
  EXPECT_EQ(rig.drive.feedback().state, DriveState::switch_on_disabled);
  rig.drive.request(DriveRequest::enable);
  rig.cycle();
  rig.cycle();
  EXPECT_EQ(rig.drive.feedback().state, DriveState::ready_to_switch_on);
  rig.cycles(3);
  EXPECT_EQ(rig.drive.feedback().state, DriveState::operation_enabled);
}

TEST(SimDrive, FollowsPositionCommandWhenEnabled) {
  Rig rig;
  rig.drive.request(DriveRequest::enable);
  rig.cycles(5);
  rig.cycles(1000, hil::DriveCommand{hil::CommandMode::position, 5000, 0.0, 0.0});
  EXPECT_NEAR(static_cast<double>(rig.drive.feedback().position_inc), 5000.0, 1.0);
}

TEST(SimDrive, IgnoresCommandWhenDisabled) {
  Rig rig;
  rig.cycles(100, hil::DriveCommand{hil::CommandMode::position, 5000, 0.0, 0.0});
  EXPECT_EQ(rig.drive.feedback().position_inc, 0);
}

TEST(SimDrive, EncoderFaultNeedsClearAndReset) {
  Rig rig;
  rig.drive.request(DriveRequest::enable);
  rig.cycles(5);
  ASSERT_TRUE(rig.drive.inject_fault("encoder", true));
  rig.cycles(2);
  EXPECT_EQ(rig.drive.feedback().state, DriveState::fault);
  EXPECT_EQ(rig.drive.feedback().fault.code, hil::make_error_code(hil::PlantFault::encoder));
  EXPECT_NE(rig.drive.feedback().fault.text.find("encoder"), std::string::npos);
  rig.drive.request(DriveRequest::fault_reset);
  rig.cycles(2);
  EXPECT_EQ(rig.drive.feedback().state, DriveState::fault) << "fault still present: reset must not clear it";
  rig.drive.inject_fault("encoder", false);
  rig.drive.request(DriveRequest::fault_reset);
  rig.cycles(2);
  EXPECT_EQ(rig.drive.feedback().state, DriveState::switch_on_disabled);
  EXPECT_FALSE(rig.drive.feedback().fault);
}

TEST(SimDrive, QuickStopRampsToRest) {
  hil::mocks::SimDriveConfig c;
  c.quick_stop_deceleration_inc_per_s2 = 1e5;
  c.plant.velocity_lag_s = 0.0;
  Rig rig(c);
  rig.drive.request(DriveRequest::enable);
  rig.cycles(5);
  rig.cycles(200, hil::DriveCommand{hil::CommandMode::velocity, 0, 10000.0, 0.0});
  ASSERT_NEAR(rig.drive.feedback().velocity_inc_per_s, 10000.0, 1.0);
  rig.drive.request(DriveRequest::quick_stop);
  rig.cycles(100, hil::DriveCommand{hil::CommandMode::velocity, 0, 10000.0, 0.0});
  const auto after_ramp = rig.drive.feedback().position_inc;
  rig.cycles(300, hil::DriveCommand{hil::CommandMode::velocity, 0, 10000.0, 0.0});
  // 10000 inc/s at 1e5 inc/s^2: 500 inc of ramp; the position loop then settles on the stop point.
  EXPECT_LT(std::llabs(rig.drive.feedback().position_inc - after_ramp), 400);
  EXPECT_EQ(rig.drive.feedback().state, DriveState::quick_stop_active);
  EXPECT_LT(std::abs(rig.drive.feedback().velocity_inc_per_s), 50.0);
}

TEST(SimDrive, HomingReferencesPosition) {
  hil::mocks::SimDriveConfig c;
  c.homing_time = 50ms;
  c.home_position_inc = 1234;
  c.plant.initial_position_inc = 777;
  Rig rig(c);
  rig.drive.request(DriveRequest::enable);
  rig.cycles(5, hil::DriveCommand{hil::CommandMode::position, 777, 0, 0});
  EXPECT_FALSE(rig.drive.feedback().referenced);
  rig.drive.request(DriveRequest::home);
  int n = 0;
  for (; n < 100; ++n) {  // read and write apart: look at the image the motion core would see
    hil::CycleTime t{rig.now, 1ms};
    rig.drive.read(t);
    if (rig.drive.feedback().referenced) break;
    rig.drive.write(t, hil::DriveCommand{hil::CommandMode::position, 777, 0, 0});
    rig.now += 1ms;
  }
  EXPECT_TRUE(rig.drive.feedback().referenced);
  EXPECT_NEAR(n, 51, 1) << "homing takes homing_time";
  EXPECT_NEAR(static_cast<double>(rig.drive.feedback().position_inc), 1234.0, 1.0);
}

TEST(SimDrive, StaleFeedbackAges) {
  Rig rig;
  rig.cycles(3);
  ASSERT_TRUE(rig.drive.inject_fault("stale_feedback", true));
  rig.cycles(20);
  EXPECT_GE(rig.drive.feedback().age, 19ms);
  EXPECT_FALSE(rig.drive.inject_fault("no_such_fault", true));
}

TEST(SimDriveConfig, ParsesAndRejects) {
  auto doc = hil::yaml::load_string("transport: sim\nkv: 40\nencoder_step: 4\nhoming_time: 0.1\n", "s.yaml");
  ASSERT_TRUE(doc);
  auto c = hil::mocks::parse_sim_drive_config(*doc, hil::yaml::Where{"s.yaml", "drive"});
  ASSERT_TRUE(c) << c.error().describe();
  EXPECT_DOUBLE_EQ(c->plant.kv_per_s, 40.0);
  EXPECT_EQ(c->plant.encoder_step_inc, 4);
  EXPECT_EQ(c->homing_time, 100ms);

  auto bad = hil::yaml::load_string("transport: sim\nkv: -3\n", "s.yaml");
  auto e = hil::mocks::parse_sim_drive_config(*bad, hil::yaml::Where{"s.yaml", "drive"});
  ASSERT_FALSE(e);
  EXPECT_EQ(e.error().describe(), "s.yaml:2:5: drive.kv: must be in (0, 10000] 1/s, got -3");

  auto typo = hil::yaml::load_string("transport: sim\nkvv: 3\n", "s.yaml");
  auto t = hil::mocks::parse_sim_drive_config(*typo, hil::yaml::Where{"s.yaml", "drive"});
  ASSERT_FALSE(t);
  EXPECT_EQ(t.error().line, 2);
}

TEST(SimDriveConfig, EveryNumericKeyHasItsDocumentedRange) {
  struct Case {
    const char* yaml;
    const char* error;
  };
  const Case cases[] = {
      {"kv: 1e9", "drive.kv: must be in (0, 10000] 1/s, got 1000000000"},
      {"kv: .nan", "drive.kv: expected a number (a finite number)"},
      {"max_velocity: 1e13", "drive.max_velocity: must be in (0, 1e+12] inc/s, got 10000000000000"},
      {"velocity_lag: 11", "drive.velocity_lag: must be in [0, 10] s, got 11"},
      {"feedforward: 1.5", "drive.feedforward: must be in [0, 1], got 1.5"},
      {"encoder_step: 2e9", "drive.encoder_step: must be in [1, 1e+09] inc, got 2000000000"},
      {"initial_position: 1e16", "drive.initial_position: must be in [-1e+15, 1e+15] inc, got 1e+16"},
      {"transition_time: 61", "drive.transition_time: must be in [0, 60] s, got 61"},
      {"quick_stop_deceleration: 0", "drive.quick_stop_deceleration: must be in (0, 1e+15] inc/s², got 0"},
      {"homing_time: 3601", "drive.homing_time: must be in [0, 3600] s, got 3601"},
      {"home_position: 2000000000000000", "drive.home_position: must be in [-1e+15, 1e+15] inc, got 2000000000000000"},
  };
  for (const auto& c : cases) {
    auto doc = hil::yaml::load_string(std::string("transport: sim\n") + c.yaml + "\n", "s.yaml");
    ASSERT_TRUE(doc);
    auto r = hil::mocks::parse_sim_drive_config(*doc, hil::yaml::Where{"s.yaml", "drive"});
    ASSERT_FALSE(r) << c.yaml;
    EXPECT_NE(r.error().describe().find(c.error), std::string::npos) << r.error().describe();
  }
}

TEST(SimDriveSwitches, ReportLimitAndHomeSwitchesAsDigitalInputs) {
  auto doc =
      hil::yaml::load_string("transport: sim\nswitches: {negative: -100, positive: 900, home: [400, 450]}\n", "s.yaml");
  ASSERT_TRUE(doc);
  auto c = hil::mocks::parse_sim_drive_config(*doc, hil::yaml::Where{"s.yaml", "drive"});
  ASSERT_TRUE(c) << c.error().describe();
  Rig rig(*c);
  EXPECT_TRUE(rig.drive.capabilities().digital_inputs);
  rig.drive.request(DriveRequest::enable);
  rig.cycles(10);
  ASSERT_EQ(rig.drive.feedback().state, DriveState::operation_enabled);
  namespace di = hil::digital_input;
  const std::pair<std::int64_t, std::uint32_t> stops[] = {
      {0, 0}, {420, di::home_switch}, {950, di::positive_limit}, {-150, di::negative_limit}, {-50, 0}};
  for (const auto& [at, bits] : stops) {
    hil::DriveCommand cmd;
    cmd.position_inc = at;
    rig.cycles(1000, cmd);
    EXPECT_EQ(rig.drive.feedback().digital_inputs, bits) << "at " << at;
  }
  rig.drive.inputs().force(di::interlock | di::negative_limit, di::interlock);  // a test's own bits
  rig.cycle();
  EXPECT_EQ(rig.drive.feedback().digital_inputs, di::interlock);
  rig.drive.inputs().release(di::negative_limit);
  rig.cycle();
  EXPECT_EQ(rig.drive.feedback().digital_inputs, di::interlock);
  hil::DriveCommand out;
  out.digital_outputs = 0x00010002u;
  rig.cycle(out);
  EXPECT_EQ(rig.drive.digital_outputs(), 0x00010002u);
}

TEST(SimDriveSwitches, BadSwitchesNameTheKey) {
  struct Case {
    const char* yaml;
    const char* error;
  };
  const Case cases[] = {
      {"switches: 5", "s.yaml:1:11: drive.switches: expected a map of switch positions"},
      {"switches: {neg: 1}",
       "s.yaml:1:12: drive.switches.neg: unknown key 'neg'; allowed here: negative, positive, home"},
      {"switches: {negative: x}", "s.yaml:1:22: drive.switches.negative: expected a number"},
      {"switches: {positive: 2e15}",
       "drive.switches.positive: must be a position in [-1e15, 1e15] inc, got 2000000000000000"},
      {"switches: {home: [5]}", "drive.switches.home: the home cam is two positions [from, to]"},
      {"switches: {home: [5, a]}", "drive.switches.home: 'a' is not a number"},
      {"switches: {home: [50, 10]}", "drive.switches.home: the cam's start 50 is after its end 10"},
      {"switches: {negative: 10, positive: 10}",
       "drive.switches.negative: the negative limit 10 must lie below the positive limit 10"},
  };
  for (const auto& c : cases) {
    auto doc = hil::yaml::load_string(c.yaml, "s.yaml");
    ASSERT_TRUE(doc) << c.yaml;
    auto r = hil::mocks::parse_sim_drive_config(*doc, hil::yaml::Where{"s.yaml", "drive"});
    ASSERT_FALSE(r) << c.yaml;
    EXPECT_NE(r.error().describe().find(c.error), std::string::npos) << c.yaml << "\n" << r.error().describe();
  }
}
