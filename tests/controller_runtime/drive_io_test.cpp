// SPDX-License-Identifier: MIT
// A drive's digital I/O on the image: the simulated drive's limit and home switches (0x60FD
// layout) reach image inputs through the axis, and image outputs reach the drive's digital
// outputs with the axis' next DriveCommand; two sinks on one axis keep to their own bits.
#include <gtest/gtest.h>

#include "hil/controllers/drive_io.hpp"
#include "hil/mocks/sim_drive.hpp"

namespace hil::controllers {
namespace {

using std::chrono::milliseconds;

class DriveIo : public ::testing::Test {
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
    d.switches.negative_inc = -5'000.0;
    d.switches.positive_inc = 40'000.0;
    d.switches.home = mocks::HomeCam{10'000.0, 12'000.0};
    auto drive = std::make_unique<mocks::SimDrive>(d);
    sim = drive.get();
    axis = std::make_unique<motion::Axis>(c, std::move(drive));
    step(milliseconds(2));
    ASSERT_FALSE(axis->enable());
    step(milliseconds(50));
  }
  /// One machine cycle: the axis, then the controller's image (inputs, logic = none, outputs).
  void step(Duration d) {
    for (const auto end = now + d; now < end;) {
      now += milliseconds(1);
      axis->update(CycleTime{now, milliseconds(1)});
      io.read_inputs(now);
      io.write_outputs(now);
    }
  }
  IoImage io{IoLayout{{1, 1, 0, 0}}};
  mocks::SimDrive* sim = nullptr;
  std::unique_ptr<motion::Axis> axis;
  TimePoint now{};
};

TEST_F(DriveIo, SwitchBitsOfTheDriveReachTheImage) {
  const BitAddress minus{IoArea::input, 0, 0}, plus{IoArea::input, 0, 1}, ref{IoArea::input, 0, 2},
      maker{IoArea::input, 0, 7};
  DriveInputs inputs(*axis, {{0, minus}, {1, plus}, {2, ref}, {20, maker}});
  io.attach(inputs);
  EXPECT_TRUE(axis->drive().capabilities().digital_inputs);
  step(milliseconds(2));
  EXPECT_FALSE(io.get(ref));
  ASSERT_FALSE(axis->move_absolute(11.0));  // onto the home cam (10..12 units)
  step(milliseconds(600));
  EXPECT_TRUE(io.get(ref));
  EXPECT_EQ(axis->digital_inputs(), digital_input::home_switch);
  EXPECT_FALSE(io.get(plus));
  ASSERT_FALSE(axis->move_absolute(41.0));  // past the positive limit switch
  step(milliseconds(1000));
  EXPECT_FALSE(io.get(ref));
  EXPECT_TRUE(io.get(plus));
  EXPECT_FALSE(io.get(minus));
  sim->inputs().force(1u << 20, 1u << 20);  // a manufacturer-specific input of the drive
  step(milliseconds(2));
  EXPECT_TRUE(io.get(maker));
  sim->inputs().release(1u << 20);
  step(milliseconds(2));
  EXPECT_FALSE(io.get(maker));
}

TEST_F(DriveIo, ImageOutputsReachTheDriveWithTheNextCommand) {
  const BitAddress brake{IoArea::output, 0, 0}, lamp{IoArea::output, 0, 1}, other{IoArea::output, 0, 2};
  DriveOutputs mine(*axis, {{16, brake}, {17, lamp}});
  DriveOutputs theirs(*axis, {{31, other}});
  io.attach(mine);
  io.attach(theirs);
  io.set(lamp, true);
  io.set(other, true);
  step(milliseconds(2));
  EXPECT_EQ(axis->digital_outputs(), (1u << 17) | (1u << 31));
  EXPECT_EQ(sim->digital_outputs(), (1u << 17) | (1u << 31)) << "carried in the axis' DriveCommand";
  io.set(lamp, false);
  io.set(brake, true);
  step(milliseconds(2));
  EXPECT_EQ(sim->digital_outputs(), (1u << 16) | (1u << 31)) << "each sink writes only its own bits";
  ASSERT_FALSE(axis->disable());
  io.set(other, false);
  step(milliseconds(2));
  EXPECT_EQ(sim->digital_outputs(), 1u << 16) << "outputs are not motion: written while disabled too";
}

}  // namespace
}  // namespace hil::controllers
