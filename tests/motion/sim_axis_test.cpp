// SPDX-License-Identifier: MIT
// The axis closing the loop over the simulated plant (hil::mocks::SimDrive: Kv loop, velocity
// lag, encoder quantisation): random moves and re-targets with limits sampled every cycle, the
// WF 725/726 dynamic window holding in normal running and tripping on an injected jam, drive
// faults and stale feedback from the mock.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "hil/mocks/sim_drive.hpp"
#include "hil/motion/axis.hpp"

namespace hil::motion {
namespace {

using std::chrono::milliseconds;

class SimAxis : public ::testing::Test {
 protected:
  void SetUp() override {
    AxisConfig c;
    c.name = "sim_x";
    c.inc_per_unit = {4096, 5};  // 819.2 inc/mm
    c.limits = {200.0, 2000.0, 40000.0};
    c.quick_stop_deceleration = 10000.0;
    c.jog_velocity = 50.0;
    c.following_error.dynamic = true;
    c.following_error.kv_per_s = 50.0;  // plant Kv
    c.following_error.min_window = 0.2;
    c.following_error.max_window = 8.0;
    c.standstill_window = 0.1;
    c.in_position_window = 0.01;
    c.in_position_timeout = milliseconds(300);
    c.soft_limit_min = -500.0;
    c.soft_limit_max = 500.0;
    ASSERT_TRUE(validate(c).has_value()) << validate(c).error();
    mocks::SimDriveConfig d;
    d.name = "sim:x";
    d.plant.kv_per_s = 50.0;
    d.plant.velocity_lag_s = 0.002;
    d.plant.max_velocity_inc_per_s = 1e7;
    d.plant.encoder_step_inc = 1;
    auto drive = std::make_unique<mocks::SimDrive>(d);
    sim = drive.get();
    axis = std::make_unique<Axis>(c, std::move(drive));
    cycle();
    ASSERT_FALSE(axis->enable());
    for (int i = 0; i < 50 && axis->status().state != AxisState::standstill; ++i) cycle();
    ASSERT_EQ(axis->status().state, AxisState::standstill) << axis->status().fault.describe();
  }
  void cycle() {
    now += milliseconds(1);
    axis->update(CycleTime{now, milliseconds(1)});
    const auto& s = axis->status();
    max_v = std::max(max_v, std::fabs(s.command_velocity));
    max_a = std::max(max_a, std::fabs(s.command_acceleration));
    max_j = std::max(max_j, std::fabs(s.command_acceleration - prev_a) / 0.001);
    prev_a = s.command_acceleration;
  }
  std::unique_ptr<Axis> axis;
  mocks::SimDrive* sim = nullptr;
  TimePoint now{};
  double max_v = 0, max_a = 0, max_j = 0, prev_a = 0;
};

TEST_F(SimAxis, RandomMovesAndRetargetsOnThePlant) {
  std::mt19937_64 rng(4242);
  std::uniform_real_distribution<double> pos(-400.0, 400.0);
  std::uniform_int_distribution<int> wait(1, 600);
  const Limits& l = axis->config().limits;
  for (int move = 0; move < 60; ++move) {
    const double target = pos(rng);
    ASSERT_FALSE(axis->move_absolute(target)) << move;
    if (move % 3 == 0) {  // re-target while moving
      for (int i = wait(rng); i > 0; --i) cycle();
      if (axis->status().state == AxisState::moving)
        ASSERT_FALSE(axis->move_absolute(pos(rng)));
      else
        ASSERT_EQ(axis->status().state, AxisState::standstill);
    }
    int n = 0;
    while ((axis->status().busy || !axis->status().in_position) && n++ < 20000) cycle();
    ASSERT_EQ(axis->status().state, AxisState::standstill) << axis->status().fault.describe();
    ASSERT_TRUE(axis->status().in_position);
    // Exact target in increments at the drive.
    EXPECT_EQ(axis->status().command_position,
              axis->scaling().to_units(axis->scaling().to_inc(axis->status().command_position)));
  }
  EXPECT_GT(now.time_since_epoch(), std::chrono::seconds(60));  // ~100k cycles of virtual time
  EXPECT_LE(max_v, l.velocity * (1 + 1e-9));
  EXPECT_LE(max_a, l.acceleration * (1 + 1e-9));
  EXPECT_LE(max_j, l.jerk * (1 + 1e-6));
}

TEST_F(SimAxis, JammedPlantTripsTheDynamicWindow) {
  ASSERT_FALSE(axis->move_absolute(300.0));
  for (int i = 0; i < 300; ++i) cycle();
  ASSERT_EQ(axis->status().state, AxisState::moving);
  ASSERT_TRUE(sim->inject_fault("following_blowup", true));
  for (int i = 0; i < 2000 && axis->status().state != AxisState::error; ++i) cycle();
  EXPECT_EQ(axis->status().fault.code, make_error_code(MotionFault::following_error_dynamic));
  EXPECT_NE(axis->status().fault.text.find("speed-dependent window"), std::string::npos);
}

TEST_F(SimAxis, EncoderFaultIsADriveFault) {
  ASSERT_FALSE(axis->move_velocity(100.0));
  for (int i = 0; i < 100; ++i) cycle();
  ASSERT_TRUE(sim->inject_fault("encoder", true));
  for (int i = 0; i < 20 && axis->status().state != AxisState::error; ++i) cycle();
  EXPECT_EQ(axis->status().fault.code, make_error_code(MotionFault::drive_fault));
  EXPECT_NE(axis->status().fault.text.find("encoder"), std::string::npos) << axis->status().fault.text;
  ASSERT_TRUE(sim->inject_fault("encoder", false));
  EXPECT_FALSE(axis->reset());
  for (int i = 0; i < 20; ++i) cycle();
  EXPECT_EQ(axis->status().state, AxisState::disabled);
  ASSERT_FALSE(axis->enable());
  for (int i = 0; i < 50 && axis->status().state != AxisState::standstill; ++i) cycle();
  EXPECT_EQ(axis->status().state, AxisState::standstill) << axis->status().fault.describe();
}

TEST_F(SimAxis, StaleFeedbackIsDriveLost) {
  // At standstill, so the frozen image does not trip the following-error window first (in
  // motion it does: the set-point runs away from a frozen actual value).
  ASSERT_TRUE(sim->inject_fault("stale_feedback", true));
  int n = 0;
  while (axis->status().state != AxisState::error && n < 100) {
    cycle();
    ++n;
  }
  EXPECT_EQ(axis->status().fault.code, make_error_code(MotionFault::drive_lost));
  EXPECT_GE(n, 20);  // feedback_timeout 20 ms
  EXPECT_LE(n, 22);
}

TEST_F(SimAxis, HomingOnTheSimDrive) {
  ASSERT_FALSE(axis->move_absolute(10.0));
  for (int i = 0; i < 2000 && axis->status().busy; ++i) cycle();
  ASSERT_FALSE(axis->home());
  for (int i = 0; i < 1000 && axis->status().state == AxisState::homing; ++i) cycle();
  EXPECT_EQ(axis->status().state, AxisState::standstill) << axis->status().fault.describe();
  EXPECT_TRUE(axis->status().referenced);
  EXPECT_NEAR(axis->status().position, 0.0, 0.01);
}

TEST_F(SimAxis, JogIntoTheSoftLimitLandsOnIt) {
  ASSERT_FALSE(axis->jog(1));
  for (int i = 0; i < 20000 && axis->status().state == AxisState::moving; ++i) cycle();
  EXPECT_EQ(axis->status().fault.code, make_error_code(MotionFault::software_limit));
  EXPECT_EQ(axis->status().command_position, 500.0);
}

TEST_F(SimAxis, SetpointOffsetShowsAsStandstillFollowingErrorAndTripsTheWindows) {
  // 0.05 mm offset (a drift's position equivalent): the plant settles there, the axis reads a
  // following error of -0.05 mm against its unchanged command, inside the standstill window 0.1.
  const double p0 = axis->status().position;
  ASSERT_FALSE(axis->set_setpoint_offset(0.05));
  EXPECT_EQ(axis->set_setpoint_offset(std::nan("")), make_error_code(MotionFault::invalid_command));
  for (int i = 0; i < 500; ++i) cycle();
  EXPECT_EQ(axis->status().state, AxisState::standstill) << axis->status().fault.describe();
  EXPECT_NEAR(axis->status().position - p0, 0.05, 2e-3);
  EXPECT_NEAR(axis->status().following_error, -0.05, 2e-3);
  EXPECT_NEAR(axis->status().command_position, p0, 1e-9) << "the offset is not the command";
  EXPECT_FALSE(axis->status().in_position) << "0.05 from the target, window 0.01";
  // A positioning towards the offset's side ends with the in-position timeout: the actual stops
  // 0.05 short of the target and never enters the window (from the other side it would pass
  // through the window and arm the standstill check there).
  ASSERT_FALSE(axis->move_relative(-5.0));
  for (int i = 0; i < 3000 && axis->status().state != AxisState::error; ++i) cycle();
  EXPECT_EQ(axis->status().fault.code, make_error_code(MotionFault::in_position_timeout));
  // Compensated (offset 0 again) the axis settles on its command and is in position.
  ASSERT_FALSE(axis->reset());
  ASSERT_FALSE(axis->set_setpoint_offset(0.0));
  for (int i = 0; i < 50 && axis->status().state != AxisState::standstill; ++i) cycle();
  if (axis->status().state == AxisState::disabled) {
    ASSERT_FALSE(axis->enable());
    for (int i = 0; i < 50 && axis->status().state != AxisState::standstill; ++i) cycle();
  }
  ASSERT_FALSE(axis->move_relative(5.0));
  for (int i = 0; i < 3000 && (axis->status().busy || !axis->status().in_position); ++i) cycle();
  EXPECT_TRUE(axis->status().in_position) << axis->status().fault.describe();
  for (int i = 0; i < 300; ++i) cycle();
  EXPECT_NEAR(axis->status().following_error, 0.0, 2e-3);
  // Beyond the standstill window at rest: standstill error.
  ASSERT_FALSE(axis->set_setpoint_offset(-0.2));
  for (int i = 0; i < 500 && axis->status().state != AxisState::error; ++i) cycle();
  EXPECT_EQ(axis->status().fault.code, make_error_code(MotionFault::standstill));
}

}  // namespace
}  // namespace hil::motion
