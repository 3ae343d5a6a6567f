// SPDX-License-Identifier: MIT
// Scenario stimuli as I/O sources: timed set and pulse, a condition, position cams (NO and NC,
// open ranges) and a registration mark latched at the crossing, on a real axis over the
// simulated drive.
#include <gtest/gtest.h>

#include "hil/controllers/io_stimulus.hpp"
#include "hil/mocks/sim_drive.hpp"

namespace hil::controllers {
namespace {

using std::chrono::milliseconds;

TEST(TimedInput, SetsAndPulsesAtScenarioTimes) {
  IoImage io(IoLayout{{1, 0, 0, 0}});
  const BitAddress a{IoArea::input, 0, 0}, b{IoArea::input, 0, 1};
  TimedInput set(a, true, milliseconds(8));
  TimedInput pulse(b, true, milliseconds(4), milliseconds(8));
  io.attach(set);
  io.attach(pulse);
  const TimePoint t0{milliseconds(100)};  // the origin is the first read, not the clock's zero
  std::vector<std::pair<bool, bool>> seen;
  for (int k = 0; k < 5; ++k) {
    io.read_inputs(t0 + milliseconds(4 * k));
    seen.emplace_back(io.get(a), io.get(b));
  }
  const std::vector<std::pair<bool, bool>> want{
      {false, false}, {false, true}, {true, true}, {true, false}, {true, false}};
  EXPECT_EQ(seen, want);
}

TEST(ConditionInput, FiresOnceTheConditionHolds) {
  IoImage io(IoLayout{{1, 0, 0, 0}});
  const BitAddress a{IoArea::input, 0, 0};
  bool cond = false;
  ConditionInput c(
      a, true, [&] { return cond; }, milliseconds(8));
  io.attach(c);
  io.read_inputs(TimePoint{});
  EXPECT_FALSE(io.get(a));
  cond = true;
  io.read_inputs(TimePoint{milliseconds(4)});
  EXPECT_TRUE(io.get(a));
  cond = false;  // latched once fired
  io.read_inputs(TimePoint{milliseconds(8)});
  EXPECT_TRUE(io.get(a));
  io.read_inputs(TimePoint{milliseconds(12)});
  EXPECT_FALSE(io.get(a)) << "pulse over";
}

class AxisStimulus : public ::testing::Test {
 protected:
  void SetUp() override {
    motion::AxisConfig c;
    c.name = "X";
    c.inc_per_unit = {1000, 1};
    c.limits = {100.0, 1000.0};
    c.quick_stop_deceleration = 5000.0;
    c.jog_velocity = 10.0;
    c.following_error.static_window = 5.0;
    c.standstill_window = 1.0;
    c.in_position_window = 0.1;
    mocks::SimDriveConfig d;
    d.plant.kv_per_s = 100.0;
    d.plant.max_velocity_inc_per_s = 1e7;
    axis = std::make_unique<motion::Axis>(c, std::make_unique<mocks::SimDrive>(d));
    step(milliseconds(2));
    ASSERT_FALSE(axis->enable());
    step(milliseconds(50));
  }
  void step(Duration d) {
    for (const auto end = now + d; now < end;) {
      now += milliseconds(1);
      axis->update(CycleTime{now, milliseconds(1)});
      if (io && (now.time_since_epoch() / milliseconds(1)) % 2 == 0) io->read_inputs(now);
    }
  }
  std::unique_ptr<motion::Axis> axis;
  std::unique_ptr<IoImage> io;
  TimePoint now{};
};

TEST_F(AxisStimulus, CamsFollowThePosition) {
  io = std::make_unique<IoImage>(IoLayout{{1, 0, 0, 0}});
  const BitAddress ref{IoArea::input, 0, 0}, limit{IoArea::input, 0, 1};
  PositionCam cam(ref, *axis, 10.0, 20.0);
  PositionCam nc_limit(limit, *axis, 45.0, std::nullopt, /*active_low=*/true);
  io->attach(cam);
  io->attach(nc_limit);
  step(milliseconds(2));
  EXPECT_FALSE(io->get(ref));
  EXPECT_TRUE(io->get(limit)) << "NC contact closed while inactive";
  ASSERT_FALSE(axis->move_absolute(15.0));
  step(milliseconds(600));
  EXPECT_TRUE(io->get(ref));
  EXPECT_TRUE(cam.active());
  ASSERT_FALSE(axis->move_absolute(50.0));
  step(milliseconds(1000));
  EXPECT_FALSE(io->get(ref));
  EXPECT_FALSE(io->get(limit)) << "limit active: NC input opens";
}

TEST_F(AxisStimulus, RegistrationMarkLatchesTheCrossing) {
  io = std::make_unique<IoImage>(IoLayout{{1, 0, 0, 0}});
  const BitAddress mark{IoArea::input, 0, 2};
  RegistrationMark m(mark, *axis, 12.3456, 0.001, milliseconds(4));
  m.reserve(8);
  io->attach(m);
  step(milliseconds(2));
  ASSERT_FALSE(axis->move_absolute(30.0));
  int pulses = 0;
  TimePoint first{};
  for (int k = 0; k < 500; ++k) {
    step(milliseconds(2));
    if (io->rising(mark)) {
      if (pulses++ == 0) first = now;
    }
  }
  EXPECT_EQ(pulses, 1);
  ASSERT_EQ(m.latches().size(), 1U);
  EXPECT_NEAR(m.latches()[0].position, 12.346, 1e-9);
  EXPECT_LE(m.latches()[0].t, first);
  EXPECT_GT(m.latches()[0].t, first - milliseconds(2)) << "interpolated inside the last cycle";
  ASSERT_FALSE(axis->move_absolute(0.0));
  step(milliseconds(1000));
  EXPECT_EQ(m.latches().size(), 2U) << "crossing back latches too";
}

}  // namespace
}  // namespace hil::controllers
