// SPDX-License-Identifier: MIT
// Axis behaviour on virtual time with a scripted drive: lifecycle, exact targets, limits sampled
// every cycle, software limits, supervision faults in the right cycle, rotary, backlash,
// re-planning, drift-free relative moves.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>

#include "hil/motion/axis.hpp"
#include "hil/motion/plan.hpp"
#include "test_drive.hpp"

namespace hil::motion {
namespace {

using std::chrono::milliseconds;
using test::TestDrive;

AxisConfig base_config() {
  AxisConfig c;
  c.name = "x";
  c.inc_per_unit = {1000, 1};  // 1 um resolution on mm
  c.limits = {100.0, 1000.0, 20000.0};
  c.quick_stop_deceleration = 5000.0;
  c.jog_velocity = 20.0;
  c.following_error.static_window = 1.0;
  c.standstill_window = 0.05;
  c.in_position_window = 0.01;
  c.in_position_timeout = milliseconds(100);
  return c;
}

class AxisTest : public ::testing::Test {
 protected:
  void make(AxisConfig c = base_config()) {
    ASSERT_TRUE(validate(c).has_value()) << validate(c).error();
    auto d = std::make_unique<TestDrive>();
    drive = d.get();
    axis = std::make_unique<Axis>(std::move(c), std::move(d));
  }
  CycleResult cycle() {
    now += period;
    const CycleResult r = axis->update(CycleTime{now, period});
    const auto& s = axis->status();
    max_v = std::max(max_v, std::fabs(s.command_velocity));
    max_a = std::max(max_a, std::fabs(s.command_acceleration));
    max_j = std::max(max_j, std::fabs(s.command_acceleration - prev_a) / 0.001);
    prev_a = s.command_acceleration;
    return r;
  }
  void run(int n) {
    for (int i = 0; i < n; ++i) cycle();
  }
  /// Cycles until not busy (bounded).
  int settle(int max = 100000) {
    int n = 0;
    do {
      cycle();
      ++n;
    } while ((axis->status().busy || axis->status().state == AxisState::moving) && n < max);
    return n;
  }
  void enable() {
    cycle();
    ASSERT_FALSE(axis->enable());
    run(3);
    ASSERT_EQ(axis->status().state, AxisState::standstill);
  }
  void reset_maxima() { max_v = max_a = max_j = 0; }
  void expect_limits(const Limits& l) {
    EXPECT_LE(max_v, l.velocity * (1 + 1e-9));
    EXPECT_LE(max_a, l.acceleration * (1 + 1e-9));
    EXPECT_LE(max_j, l.jerk * (1 + 1e-6));
  }

  std::unique_ptr<Axis> axis;
  TestDrive* drive = nullptr;
  TimePoint now{};
  Duration period = milliseconds(1);
  double max_v = 0, max_a = 0, max_j = 0, prev_a = 0;
};

TEST_F(AxisTest, EnableWalksTheDriveToOperationEnabled) {
  make();
  cycle();
  EXPECT_EQ(axis->status().state, AxisState::disabled);
  EXPECT_EQ(axis->move_absolute(1.0), make_error_code(MotionFault::not_enabled));
  EXPECT_FALSE(axis->enable());
  EXPECT_EQ(axis->status().state, AxisState::enabling);
  ASSERT_EQ(drive->requests.back(), DriveRequest::enable);
  cycle();
  EXPECT_EQ(axis->status().state, AxisState::enabling);
  cycle();  // drive enabled at this write; seen next read
  cycle();
  EXPECT_EQ(axis->status().state, AxisState::standstill);
  EXPECT_TRUE(axis->status().in_position);
  EXPECT_FALSE(axis->disable());
  EXPECT_EQ(drive->requests.back(), DriveRequest::disable);
  EXPECT_EQ(axis->status().state, AxisState::disabled);
}

TEST_F(AxisTest, EnableTimesOut) {
  AxisConfig c = base_config();
  c.enable_timeout = milliseconds(50);
  make(c);
  drive->never_enable = true;
  cycle();
  const TimePoint asked = now;
  ASSERT_FALSE(axis->enable());
  while (axis->status().state == AxisState::enabling) cycle();
  EXPECT_EQ(now - asked, milliseconds(51));
  EXPECT_EQ(axis->status().fault.code, make_error_code(MotionFault::not_enabled));
  EXPECT_NE(axis->status().fault.text.find("operation_enabled within 50 ms"), std::string::npos);
}

TEST_F(AxisTest, MoveAbsoluteReachesTargetExactlyInIncrementsWithinLimits) {
  make();
  enable();
  reset_maxima();
  ASSERT_FALSE(axis->move_absolute(12.3456789));
  const int n = settle();
  expect_limits(axis->config().limits);
  EXPECT_EQ(drive->written(), 12346);  // round(12345.6789)
  EXPECT_EQ(axis->status().command_position, 12.346);
  EXPECT_EQ(axis->status().state, AxisState::standstill);
  EXPECT_TRUE(axis->status().in_position);
  EXPECT_FALSE(axis->status().busy);
  // Optimal duration (rest to rest) within one cycle.
  const double t_opt = rest_to_rest_duration(12.346, axis->config().limits);
  EXPECT_NEAR(n * 0.001, t_opt, 0.0015);
}

TEST_F(AxisTest, TrapezoidalAxis) {
  AxisConfig c = base_config();
  c.limits.jerk = std::numeric_limits<double>::infinity();
  make(c);
  enable();
  reset_maxima();
  ASSERT_FALSE(axis->move_absolute(-7.5));
  const int n = settle();
  EXPECT_LE(max_v, c.limits.velocity * (1 + 1e-9));
  EXPECT_LE(max_a, c.limits.acceleration * (1 + 1e-9));
  EXPECT_EQ(drive->written(), -7500);
  EXPECT_NEAR(n * 0.001, 7.5 / 100.0 + 100.0 / 1000.0, 0.0015);  // cruise + one ramp time
}

TEST_F(AxisTest, RejectsNonsense) {
  make();
  enable();
  EXPECT_EQ(axis->move_absolute(std::nan("")), make_error_code(MotionFault::invalid_command));
  EXPECT_EQ(axis->move_relative(1e300), make_error_code(MotionFault::invalid_command));
  EXPECT_EQ(axis->move_absolute(-1e13), make_error_code(MotionFault::invalid_command));  // 1e16 increments
  EXPECT_EQ(axis->move_absolute(1.0, Direction::shortest, Limits{-1.0, 1.0, 1.0}),
            make_error_code(MotionFault::invalid_command));
  EXPECT_EQ(axis->move_velocity(101.0), make_error_code(MotionFault::invalid_command));
  EXPECT_EQ(axis->move_absolute(1.0, Direction::shortest, Limits{100.0, 1001.0, 20000.0}),
            make_error_code(MotionFault::invalid_command));  // above the machine's acceleration
  EXPECT_EQ(axis->move_relative(1.0, Limits{100.0, 1000.0, std::numeric_limits<double>::infinity()}),
            make_error_code(MotionFault::invalid_command));  // trapezoid on a jerk-limited axis
  EXPECT_EQ(axis->jog(2), make_error_code(MotionFault::invalid_command));
  AxisConfig bad = base_config();
  bad.limits.jerk = -1;
  EXPECT_FALSE(validate(bad).has_value());
  EXPECT_NE(validate(bad).error().find("limits.jerk"), std::string::npos);
  bad = base_config();
  bad.in_position_window = 0.1;
  EXPECT_NE(validate(bad).error().find("in_position_window"), std::string::npos);
  bad = base_config();
  bad.rotary = true;
  bad.modulo = 360.0;
  bad.inc_per_unit = {1000, 7};  // 51428.57 inc per turn
  EXPECT_NE(validate(bad).error().find("whole number"), std::string::npos);
  Axis broken(bad, std::make_unique<TestDrive>());
  EXPECT_EQ(broken.status().state, AxisState::error);
}

TEST_F(AxisTest, NewTargetWhileMovingStaysWithinLimitsAndEndsExactly) {
  make();
  enable();
  reset_maxima();
  ASSERT_FALSE(axis->move_absolute(100.0));
  run(300);  // cruising at 100 mm/s
  ASSERT_EQ(axis->status().state, AxisState::moving);
  ASSERT_FALSE(axis->move_absolute(20.0));  // behind the braking point: reverse
  settle();
  expect_limits(axis->config().limits);
  EXPECT_EQ(drive->written(), 20000);
  ASSERT_FALSE(axis->move_absolute(80.0));
  run(100);
  ASSERT_FALSE(axis->move_absolute(81.0, Direction::shortest, Limits{50.0, 500.0, 5000.0}));  // slower limits ahead
  settle();
  EXPECT_EQ(drive->written(), 81000);
  EXPECT_LE(max_v, 100.0 * (1 + 1e-9));
}

TEST_F(AxisTest, StopAndQuickStopMidMove) {
  make();
  enable();
  ASSERT_FALSE(axis->move_absolute(100.0));
  run(400);
  reset_maxima();
  const double p0 = axis->status().command_position;
  ASSERT_FALSE(axis->stop());
  EXPECT_EQ(axis->status().state, AxisState::stopping);
  settle();
  expect_limits(axis->config().limits);
  const double stop_dist = axis->status().command_position - p0;
  EXPECT_EQ(axis->status().state, AxisState::standstill);
  EXPECT_EQ(axis->status().command_velocity, 0.0);
  ASSERT_FALSE(axis->move_absolute(0.0));
  run(400);
  const double p1 = axis->status().command_position;
  ASSERT_FALSE(axis->quick_stop());
  settle();
  EXPECT_LT(std::fabs(axis->status().command_position - p1), stop_dist / 2);
  EXPECT_EQ(axis->status().state, AxisState::standstill);
}

TEST_F(AxisTest, AbsoluteTargetBeyondSoftLimitIsRejected) {
  AxisConfig c = base_config();
  c.soft_limit_min = -10.0;
  c.soft_limit_max = 50.0;
  make(c);
  enable();
  EXPECT_EQ(axis->move_absolute(50.001), make_error_code(MotionFault::software_limit));
  EXPECT_EQ(axis->move_absolute(-10.5), make_error_code(MotionFault::software_limit));
  EXPECT_EQ(axis->move_relative(60.0), make_error_code(MotionFault::software_limit));
  EXPECT_FALSE(axis->move_absolute(50.0));
}

TEST_F(AxisTest, CoarseIncrementsStopInsideTheSoftLimits) {
  // 7 mm per increment: the limits 54 and -54 lie past the middle of their increments (56, -56),
  // so the nearest increment of a target at the limit is beyond it. Moves stop on 49 / -49.
  AxisConfig c = base_config();
  c.inc_per_unit = {1, 7};
  c.soft_limit_max = 54.0;
  c.soft_limit_min = -54.0;
  make(c);
  enable();
  ASSERT_FALSE(axis->move_absolute(53.0));
  settle();
  EXPECT_EQ(drive->written(), 7);
  EXPECT_LE(axis->status().command_position, 54.0);
  ASSERT_FALSE(axis->move_absolute(-54.0));
  settle();
  EXPECT_EQ(drive->written(), -7);
  EXPECT_GE(axis->status().command_position, -54.0);
  // A velocity move onto the limit stops on the inner increment too (the fault says which limit).
  ASSERT_FALSE(axis->move_velocity(80.0));
  while (axis->status().state == AxisState::moving) cycle();
  EXPECT_EQ(drive->written(), 7);
  EXPECT_LE(axis->status().command_position, 54.0);
  EXPECT_EQ(axis->status().fault.code, make_error_code(MotionFault::software_limit));
}

TEST_F(AxisTest, JogTowardsSoftLimitStopsExactlyOnIt) {
  AxisConfig c = base_config();
  c.soft_limit_max = 10.0;
  c.soft_limit_min = -3.0;
  make(c);
  enable();
  reset_maxima();
  ASSERT_FALSE(axis->move_velocity(80.0));
  std::int64_t max_cmd = 0;
  while (axis->status().state == AxisState::moving) {
    cycle();
    max_cmd = std::max(max_cmd, drive->written());
  }
  expect_limits(c.limits);
  EXPECT_EQ(max_cmd, 10000);
  EXPECT_EQ(drive->written(), 10000);
  EXPECT_EQ(axis->status().state, AxisState::error);
  EXPECT_EQ(axis->status().fault.code, make_error_code(MotionFault::software_limit));
  EXPECT_NE(axis->status().fault.text.find("positive software limit 10 reached"), std::string::npos)
      << axis->status().fault.text;
  EXPECT_FALSE(axis->reset());
  EXPECT_EQ(axis->status().state, AxisState::standstill);
  EXPECT_EQ(axis->jog(1), make_error_code(MotionFault::software_limit));  // at the limit: no further
  ASSERT_FALSE(axis->jog(-1));
  std::int64_t min_cmd = 10000;
  while (axis->status().state == AxisState::moving) {
    cycle();
    min_cmd = std::min(min_cmd, drive->written());
  }
  EXPECT_EQ(min_cmd, -3000);
  EXPECT_EQ(drive->written(), -3000);
}

TEST_F(AxisTest, FollowingErrorFaultFiresInTheRightCycle) {
  make();
  enable();
  ASSERT_FALSE(axis->move_absolute(50.0));
  run(100);
  drive->follow = false;  // mechanics jam: the actual position freezes here
  const std::int64_t frozen = drive->position;
  for (int i = 0; i < 1000; ++i) {
    // FE this cycle = the command written last cycle - the frozen actual.
    const bool expect = static_cast<double>(drive->written() - frozen) / 1000.0 > 1.0;
    cycle();
    ASSERT_EQ(axis->status().state == AxisState::error, expect) << "cycle " << i;
    if (expect) break;
  }
  EXPECT_EQ(axis->status().fault.code, make_error_code(MotionFault::following_error));
  EXPECT_NE(axis->status().fault.text.find("static window 1"), std::string::npos) << axis->status().fault.text;
  // Reaction quick stop: the set-point brakes and comes to rest.
  settle();
  EXPECT_EQ(axis->status().command_velocity, 0.0);
  EXPECT_EQ(axis->update(CycleTime{now, period}), CycleResult::fault);
}

TEST_F(AxisTest, DynamicWindowFaultFiresInTheRightCycle) {
  AxisConfig c = base_config();
  c.following_error.dynamic = true;
  c.following_error.kv_per_s = 100.0;
  c.following_error.min_window = 0.2;
  c.following_error.max_window = 5.0;
  make(c);
  drive->lag = 15;  // FE in cruise = 100 mm/s * 15 ms = 1.5 mm, window 1.5 * 100 / 100 = 1.5 (>, not >=)
  enable();
  ASSERT_FALSE(axis->move_absolute(60.0));
  settle();
  ASSERT_EQ(axis->status().state, AxisState::standstill) << axis->status().fault.describe();
  drive->lag = 16;  // 1.6 mm: must trip
  ASSERT_FALSE(axis->move_absolute(0.0));
  for (int i = 0; i < 2000; ++i) {
    const bool expect = std::fabs(static_cast<double>(drive->written() - drive->position)) / 1000.0 > 1.5 + 1e-9;
    cycle();
    ASSERT_EQ(axis->status().state == AxisState::error, expect) << "cycle " << i;
    if (expect) break;
  }
  EXPECT_EQ(axis->status().fault.code, make_error_code(MotionFault::following_error_dynamic));
}

TEST_F(AxisTest, StandstillFaultFiresInTheCycleTheAxisIsPushed) {
  make();
  enable();
  ASSERT_FALSE(axis->move_absolute(5.0));
  settle();
  ASSERT_TRUE(axis->status().in_position);
  drive->follow = false;
  drive->position = 5040;  // 0.04 < 0.05: tolerated
  run(10);
  EXPECT_EQ(axis->status().state, AxisState::standstill);
  EXPECT_FALSE(axis->status().in_position);  // outside +-0.01
  drive->position = 5051;
  cycle();
  EXPECT_EQ(axis->status().state, AxisState::error);
  EXPECT_EQ(axis->status().fault.code, make_error_code(MotionFault::standstill));
  // Reset: holds where it stands now.
  EXPECT_FALSE(axis->reset());
  cycle();
  EXPECT_EQ(axis->status().state, AxisState::standstill);
  EXPECT_EQ(drive->written(), 5051);
}

TEST_F(AxisTest, InPositionTimeout) {
  make();
  drive->offset = 20;  // the drive stays 0.02 short: outside +-0.01, inside every other window
  enable();
  // The standstill check at enable sees the offset only once a command moved the drive.
  ASSERT_FALSE(axis->move_absolute(1.0));
  TimePoint done{};
  while (axis->status().state != AxisState::error) {
    cycle();
    if (!axis->status().busy && done == TimePoint{}) done = now;
    ASSERT_LT(now.time_since_epoch(), std::chrono::seconds(2));
  }
  EXPECT_EQ(axis->status().fault.code, make_error_code(MotionFault::in_position_timeout));
  EXPECT_EQ(now - done, milliseconds(101));
}

TEST_F(AxisTest, DriveFaultAndReset) {
  make();
  enable();
  ASSERT_FALSE(axis->move_absolute(10.0));
  run(50);
  drive->fault = hil::Fault{make_error_code(PlantFault::encoder), "encoder lost"};
  EXPECT_EQ(cycle(), CycleResult::fault);
  EXPECT_EQ(axis->status().fault.code, make_error_code(MotionFault::drive_fault));
  EXPECT_NE(axis->status().fault.text.find("encoder lost"), std::string::npos);
  EXPECT_EQ(axis->move_absolute(1.0), make_error_code(MotionFault::invalid_command));
  EXPECT_FALSE(axis->reset());
  EXPECT_EQ(drive->requests.back(), DriveRequest::fault_reset);
  cycle();
  EXPECT_EQ(axis->status().state, AxisState::disabled);
  EXPECT_FALSE(axis->enable());
  run(3);
  EXPECT_EQ(axis->status().state, AxisState::standstill);
}

TEST_F(AxisTest, StaleFeedbackIsDriveLost) {
  make();
  enable();
  ASSERT_FALSE(axis->move_velocity(50.0));
  run(100);
  drive->age = milliseconds(21);
  cycle();
  EXPECT_EQ(axis->status().fault.code, make_error_code(MotionFault::drive_lost));
  EXPECT_TRUE(axis->status().busy);  // quick stop ramp runs
  settle();
  EXPECT_EQ(axis->status().command_velocity, 0.0);
}

TEST_F(AxisTest, DisableReaction) {
  AxisConfig c = base_config();
  c.reaction = FaultReaction::disable;
  make(c);
  enable();
  ASSERT_FALSE(axis->move_absolute(10.0));
  run(50);
  drive->follow = false;
  drive->position -= 5000;
  cycle();
  EXPECT_EQ(axis->status().state, AxisState::error);
  EXPECT_EQ(drive->requests.back(), DriveRequest::disable);
  EXPECT_FALSE(axis->status().busy);
}

TEST_F(AxisTest, HomingThroughTheDrive) {
  make();
  enable();
  ASSERT_FALSE(axis->move_absolute(3.0));
  settle();
  ASSERT_FALSE(axis->home());
  EXPECT_EQ(axis->status().state, AxisState::homing);
  run(10);
  EXPECT_EQ(axis->status().state, AxisState::standstill);
  EXPECT_TRUE(axis->status().referenced);
  EXPECT_EQ(axis->status().position, 0.0);
  ASSERT_FALSE(axis->move_absolute(1.0));
  settle();
  EXPECT_EQ(drive->written(), 1000);
  drive->homing_supported = false;
  EXPECT_EQ(axis->home(), make_error_code(MotionFault::invalid_command));
}

TEST_F(AxisTest, RotaryShortestAndFixedDirection) {
  AxisConfig c = base_config();
  c.rotary = true;
  c.modulo = 360.0;
  c.inc_per_unit = {10, 1};
  c.limits = {360.0, 3600.0, 36000.0};
  c.jog_velocity = 90.0;
  c.quick_stop_deceleration = 7200.0;
  make(c);
  enable();
  ASSERT_FALSE(axis->move_absolute(350.0));  // shortest from 0: -10 degrees
  settle();
  EXPECT_EQ(drive->written(), -100);
  EXPECT_DOUBLE_EQ(axis->status().position, 350.0);
  ASSERT_FALSE(axis->move_absolute(10.0));  // shortest: +20 through 0
  std::int64_t lo = 0;
  while (axis->status().busy || axis->status().state == AxisState::moving) {
    cycle();
    lo = std::min(lo, drive->written());
  }
  EXPECT_EQ(drive->written(), 100);
  EXPECT_GE(lo, -100);
  ASSERT_FALSE(axis->move_absolute(5.0, Direction::positive));  // +355
  settle();
  EXPECT_EQ(drive->written(), 100 + 3550);
  EXPECT_DOUBLE_EQ(axis->status().position, 5.0);
  ASSERT_FALSE(axis->move_absolute(5.0 + 720.0, Direction::negative));  // same angle: no motion
  settle();
  EXPECT_EQ(drive->written(), 3650);
  ASSERT_FALSE(axis->move_absolute(6.0, Direction::negative));  // -359
  settle();
  EXPECT_EQ(drive->written(), 3650 - 3590);
  EXPECT_DOUBLE_EQ(axis->status().command_position, 6.0);
}

TEST_F(AxisTest, BacklashAddedOnReversalNotShown) {
  AxisConfig c = base_config();
  c.backlash = 0.1;
  make(c);
  enable();
  ASSERT_FALSE(axis->move_absolute(10.0));
  settle();
  EXPECT_EQ(drive->written(), 10000);  // first approach positive: no offset
  ASSERT_FALSE(axis->move_absolute(5.0));
  settle();
  EXPECT_EQ(drive->written(), 5000 - 100);  // negative approach: -backlash at the drive
  EXPECT_EQ(axis->status().command_position, 5.0);
  EXPECT_TRUE(axis->status().in_position);
  ASSERT_FALSE(axis->move_absolute(6.0));
  settle();
  EXPECT_EQ(drive->written(), 6000);
  EXPECT_EQ(axis->status().command_position, 6.0);
}

TEST_F(AxisTest, RelativeMovesDoNotDrift) {
  AxisConfig c = base_config();
  c.inc_per_unit = {4096, 5};  // 819.2 inc/mm
  make(c);
  enable();
  for (int i = 0; i < 1000; ++i) {
    ASSERT_FALSE(axis->move_relative(0.001));
    run(2);
    ASSERT_FALSE(axis->move_relative(0.0));  // re-issue from the same target: no change
  }
  settle();
  EXPECT_EQ(drive->written(), 819);  // round(1000 * 0.8192)
  for (int i = 0; i < 1000; ++i) ASSERT_FALSE(axis->move_relative(-0.001));
  settle();
  EXPECT_EQ(drive->written(), 0);
}

TEST_F(AxisTest, VelocityMoveAndJog) {
  make();
  enable();
  reset_maxima();
  ASSERT_FALSE(axis->move_velocity(-40.0));
  run(500);
  EXPECT_EQ(axis->status().command_velocity, -40.0);
  EXPECT_EQ(axis->status().state, AxisState::moving);
  ASSERT_FALSE(axis->jog(1));  // reverse into jog
  run(500);
  EXPECT_EQ(axis->status().command_velocity, 20.0);
  ASSERT_FALSE(axis->stop());
  settle();
  expect_limits(axis->config().limits);
  EXPECT_EQ(axis->status().state, AxisState::standstill);
  EXPECT_TRUE(axis->status().in_position);
}

TEST_F(AxisTest, RandomCommandStreamKeepsLimitsAndLandsExactly) {
  AxisConfig c = base_config();
  c.soft_limit_min = -200.0;
  c.soft_limit_max = 200.0;
  make(c);
  enable();
  std::mt19937_64 rng(31337);
  std::uniform_real_distribution<double> pos(-200.0, 200.0), u(0.0, 1.0);
  std::uniform_int_distribution<int> wait(1, 400), what(0, 9);
  const Limits& l = c.limits;
  const double qs_jerk = l.jerk * c.quick_stop_deceleration / l.acceleration;
  double worst_v = 0, worst_a = 0, worst_j = 0;
  bool quick = false;
  for (int k = 0; k < 400; ++k) {
    const int w = what(rng);
    std::error_code ec;
    if (w <= 3)
      ec = axis->move_absolute(pos(rng));
    else if (w == 4)
      ec = axis->move_relative(pos(rng) / 4);
    else if (w == 5)
      ec = axis->move_velocity((u(rng) - 0.5) * 2 * l.velocity);
    else if (w == 6)
      ec = axis->stop();
    else if (w == 7) {
      ec = axis->quick_stop();
      quick = true;
    } else if (w == 8)
      ec = axis->move_absolute(pos(rng), Direction::shortest,
                               Limits{l.velocity * (0.1 + 0.9 * u(rng)), l.acceleration / 2, l.jerk / 2});
    else
      ec = axis->jog(u(rng) < 0.5 ? -1 : 1);
    ASSERT_TRUE(!ec || ec == make_error_code(MotionFault::software_limit)) << ec.message();
    for (int i = wait(rng); i > 0; --i) {
      cycle();
      ASSERT_LE(std::fabs(axis->status().command_position), 200.0 + 1e-9);
      if (axis->status().state == AxisState::error) {
        ASSERT_EQ(axis->status().fault.code, make_error_code(MotionFault::software_limit)) << axis->status().fault.text;
        settle();
        ASSERT_FALSE(axis->reset());
      }
    }
    worst_v = std::max(worst_v, max_v);
    worst_a = std::max(worst_a, max_a);
    worst_j = std::max(worst_j, max_j);
    reset_maxima();
  }
  EXPECT_LE(worst_v, l.velocity * (1 + 1e-9));
  EXPECT_LE(worst_a, (quick ? c.quick_stop_deceleration : l.acceleration) * (1 + 1e-9));
  EXPECT_LE(worst_j, (quick ? qs_jerk : l.jerk) * (1 + 1e-6));
  ASSERT_FALSE(axis->move_absolute(123.456));
  settle();
  EXPECT_EQ(drive->written(), 123456);
}

TEST_F(AxisTest, DriveProfileDriveGetsEachMoveAndIsSupervisedAtTheEndOnly) {
  AxisConfig c = base_config();
  c.backlash = 0.1;
  make(c);
  drive->drive_profile = true;  // jumps to the target at once: 10 mm ahead of the reference
  enable();
  EXPECT_EQ(drive->commands.back().move.kind, DriveMove::Kind::hold);
  ASSERT_FALSE(axis->move_absolute(10.0));
  cycle();
  const auto first = drive->commands.back().move;
  EXPECT_EQ(first.kind, DriveMove::Kind::position);
  EXPECT_EQ(first.target_inc, 10000);
  EXPECT_DOUBLE_EQ(first.velocity_inc_per_s, 100'000.0);
  EXPECT_DOUBLE_EQ(first.acceleration_inc_per_s2, 1'000'000.0);
  settle();
  // The path was far outside the 1 mm static window, yet no fault: the drive watches its own.
  EXPECT_EQ(axis->status().state, AxisState::standstill) << axis->status().fault.describe();
  EXPECT_TRUE(axis->status().in_position);
  EXPECT_EQ(drive->commands.back().move.id, first.id) << "the move stays until the next command";

  // Reversal: the target carries the backlash of the negative approach.
  ASSERT_FALSE(axis->move_absolute(5.0));
  cycle();
  EXPECT_EQ(drive->commands.back().move.target_inc, 5000 - 100);
  EXPECT_NE(drive->commands.back().move.id, first.id);
  settle();
  EXPECT_EQ(axis->status().state, AxisState::standstill) << axis->status().fault.describe();
  EXPECT_TRUE(axis->status().in_position);

  // Velocity moves hand over the signed velocity; stop() turns into a hold under the move's deceleration.
  ASSERT_FALSE(axis->move_velocity(-30.0));
  cycle();
  EXPECT_EQ(drive->commands.back().move.kind, DriveMove::Kind::velocity);
  EXPECT_DOUBLE_EQ(drive->commands.back().move.velocity_inc_per_s, -30'000.0);
  run(50);
  ASSERT_FALSE(axis->stop());
  cycle();
  EXPECT_EQ(drive->commands.back().move.kind, DriveMove::Kind::hold);
  EXPECT_DOUBLE_EQ(drive->commands.back().move.deceleration_inc_per_s2, 1'000'000.0);
}

TEST_F(AxisTest, DriveProfileDriveThatNeverArrivesFaultsInPositionTimeout) {
  make();
  drive->drive_profile = true;
  drive->offset = 500;  // stops 0.5 mm short
  enable();
  ASSERT_FALSE(axis->move_absolute(10.0));
  settle();
  for (int i = 0; i < 200 && axis->status().state != AxisState::error; ++i) cycle();
  ASSERT_EQ(axis->status().state, AxisState::error);
  EXPECT_EQ(axis->status().fault.code, make_error_code(MotionFault::in_position_timeout));
  EXPECT_EQ(drive->commands.back().move.kind, DriveMove::Kind::hold) << "a faulted axis makes the drive brake";
}

}  // namespace
}  // namespace hil::motion
