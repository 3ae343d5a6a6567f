// SPDX-License-Identifier: MIT
// The Controller base on a real axis over the simulated drive: the order of one controller
// cycle (sources, logic, sinks), a software-limit stop and a limit-switch hit raised in the
// device's numbers (WF 725/726 96 and 16) with the catalogue's reaction, acknowledgement that
// resets the axis, and errors raised by the device logic.
#include <gtest/gtest.h>

#include <vector>

#include "hil/controllers/controller.hpp"
#include "hil/mocks/sim_drive.hpp"
#include "hil/profiles/loader.hpp"

namespace hil::controllers {
namespace {

using std::chrono::milliseconds;

const BitAddress start_in{IoArea::input, 0, 0};
const BitAddress limit_plus{IoArea::input, 0, 1};
const BitAddress limit_minus{IoArea::input, 0, 2};
const BitAddress running_out{IoArea::output, 0, 0};

motion::AxisConfig axis_config() {
  motion::AxisConfig c;
  c.name = "X";
  c.inc_per_unit = {1000, 1};
  c.limits = {100.0, 1000.0};
  c.quick_stop_deceleration = 5000.0;
  c.jog_velocity = 10.0;
  c.following_error.static_window = 5.0;
  c.standstill_window = 1.0;
  c.in_position_window = 0.1;
  c.soft_limit_min = -50.0;
  c.soft_limit_max = 50.0;
  return c;
}

/// A minimal device: output 0.0 follows "axis busy", input 0.0 starts a move; WF numbering.
class TestController final : public Controller {
 public:
  explicit TestController(std::shared_ptr<const profiles::Profile> p, bool nc = false)
      : Controller(p, profiles::ParameterSet{}, IoLayout{{2, 2, 2, 0}}, milliseconds(4)) {
    traversing = catalogue("traversing");
    ControllerAxis a;
    a.name = "X";
    a.config = axis_config();
    a.limit_switches = {limit_minus, limit_plus, nc};
    add_axis(std::move(a));
    (void)io().name_bit("start", start_in);
  }
  void on_cycle(const CycleTime& cycle) noexcept override {
    ++cycles;
    saw_start.push_back(io().get(start_in));
    if (io().rising(start_in)) (void)axis(0).move_velocity(target_velocity);
    io().set(running_out, axis(0).status().busy);
    if (raise_drive_off) {
      raise(*traversing, 0x14, cycle.now, 0, "test");  // drive not ready: drive_off
      raise_drive_off = false;
    }
  }
  std::optional<DeviceErrorCode> map_axis_fault(std::size_t, const hil::Fault& f,
                                                const motion::AxisStatus& st) const noexcept override {
    if (f.code == hil::MotionFault::software_limit) return DeviceErrorCode{traversing, st.position > 0 ? 0x96 : 0x95};
    if (f.code == ControllerFault::hard_limit_positive) return DeviceErrorCode{traversing, 0x16};
    if (f.code == ControllerFault::hard_limit_negative) return DeviceErrorCode{traversing, 0x15};
    return std::nullopt;
  }
  const profiles::ErrorCatalogue* traversing = nullptr;
  double target_velocity = 40.0;
  int cycles = 0;
  bool raise_drive_off = false;
  std::vector<bool> saw_start;
};

struct Script : IoSource {
  std::vector<std::pair<TimePoint, std::pair<BitAddress, bool>>> events;
  void read(TimePoint now, IoImage& image) noexcept override {
    for (const auto& [t, e] : events)
      if (t <= now) image.set(e.first, e.second);
  }
};

struct OutputLog : IoSink {
  std::vector<bool> running;
  void write(TimePoint, const IoImage& image) noexcept override { running.push_back(image.get(running_out)); }
};

class ControllerRun : public ::testing::Test {
 protected:
  void make(bool nc = false) {
    auto p = profiles::find_profile("wf725-726");
    ASSERT_TRUE(p) << p.error().describe();
    ctl = std::make_unique<TestController>(*p, nc);
    mocks::SimDriveConfig d;
    d.name = "sim:x";
    d.plant.kv_per_s = 100.0;
    d.plant.max_velocity_inc_per_s = 1e7;
    ax = std::make_unique<motion::Axis>(ctl->axis_specs()[0].config, std::make_unique<mocks::SimDrive>(d));
    motion::Axis* axes[] = {ax.get()};
    ASSERT_TRUE(ctl->bind_axes(axes));
    ctl->io().attach(script);
    ctl->io().attach(log);
    if (nc)
      script.events.push_back({TimePoint{}, {limit_plus, true}}),
          script.events.push_back({TimePoint{}, {limit_minus, true}});
    run(milliseconds(4));
    ASSERT_FALSE(ax->enable());
    run(milliseconds(100));
    ASSERT_EQ(ax->status().state, motion::AxisState::standstill) << ax->status().fault.describe();
  }
  /// Axis every 1 ms, controller every 4 ms (after the axis update of that cycle).
  void run(Duration d) {
    const auto end = now + d;
    while (now < end) {
      now += milliseconds(1);
      ax->update(CycleTime{now, milliseconds(1)});
      if (++tick % 4 == 0) ctl->step(CycleTime{now, milliseconds(4)});
    }
  }
  std::unique_ptr<TestController> ctl;
  std::unique_ptr<motion::Axis> ax;
  Script script;
  OutputLog log;
  TimePoint now{};
  long tick = 0;
};

TEST_F(ControllerRun, CycleReadsInputsRunsLogicWritesOutputs) {
  make();
  EXPECT_EQ(ctl->cycle_period(), milliseconds(4));
  EXPECT_EQ(ctl->device(), "wf725-726");
  const int before = ctl->cycles;
  script.events.push_back({now + milliseconds(10), {start_in, true}});
  ctl->target_velocity = 10.0;
  run(milliseconds(40));
  EXPECT_EQ(ctl->cycles - before, 10);
  ASSERT_EQ(log.running.size(), static_cast<std::size_t>(ctl->cycles));
  // The start is seen from the first controller cycle at or after t+10 ms, the move runs and
  // the sink sees the output the logic set in the same cycle.
  EXPECT_TRUE(ctl->saw_start.back());
  EXPECT_TRUE(log.running.back());
  EXPECT_EQ(ctl->resolve_bit("start"), start_in);
  EXPECT_FALSE(ctl->resolve_bit("nope"));
}

TEST_F(ControllerRun, SoftwareLimitStopIsTheDevicesError) {
  make();
  script.events.push_back({now, {start_in, true}});
  run(milliseconds(2000));
  ASSERT_EQ(ax->status().state, motion::AxisState::error);
  EXPECT_EQ(ax->status().fault.code, hil::MotionFault::software_limit);
  ASSERT_EQ(ctl->errors().active().size(), 1U);
  const auto& e = ctl->errors().active()[0];
  EXPECT_EQ(e.code_text(), "96");
  EXPECT_EQ(e.cause, hil::MotionFault::software_limit);
  EXPECT_EQ(e.axis, 0);
  EXPECT_NE(e.describe().find("Pre-limit switch positive (MD 13)"), std::string::npos) << e.describe();
  EXPECT_NE(e.describe().find("axis X"), std::string::npos) << e.describe();
  EXPECT_NEAR(ax->status().position, 50.0, 0.05);
  EXPECT_EQ(ctl->step(CycleTime{now, milliseconds(4)}), ControllerStatus::error);
  run(milliseconds(100));
  EXPECT_EQ(ctl->errors().history().size(), 1U) << "raised once per fault";
  EXPECT_EQ(ctl->acknowledge(Acknowledgement::acknowledge), 1U);
  run(milliseconds(20));
  EXPECT_EQ(ax->status().state, motion::AxisState::standstill) << "acknowledge reset the axis";
  EXPECT_FALSE(ctl->errors().any());
}

TEST_F(ControllerRun, LimitSwitchStopsAnAxisMovingOntoIt) {
  make();
  script.events.push_back({now, {start_in, true}});
  script.events.push_back({now + milliseconds(300), {limit_plus, true}});
  run(milliseconds(290));
  EXPECT_EQ(ax->status().state, motion::AxisState::moving);
  run(milliseconds(200));
  ASSERT_EQ(ctl->errors().active().size(), 1U);
  const auto& e = ctl->errors().active()[0];
  EXPECT_EQ(e.code_text(), "16");
  EXPECT_EQ(e.cause, ControllerFault::hard_limit_positive);
  EXPECT_EQ(e.reaction, profiles::Reaction::drive_off);
  EXPECT_LT(ax->status().position, 20.0) << "stopped well before the soft limit";
  EXPECT_NE(ax->status().state, motion::AxisState::moving);
  // Moving away from the active switch is allowed once acknowledged.
  ctl->acknowledge(Acknowledgement::acknowledge);
  run(milliseconds(20));
  ASSERT_FALSE(ax->enable());
  run(milliseconds(100));
  ASSERT_FALSE(ax->move_velocity(-10.0));
  run(milliseconds(100));
  EXPECT_EQ(ax->status().state, motion::AxisState::moving);
  EXPECT_FALSE(ctl->errors().any());
}

TEST_F(ControllerRun, NormallyClosedSwitchIsActiveAtZero) {
  make(/*nc=*/true);
  script.events.push_back({now, {start_in, true}});
  script.events.push_back({now + milliseconds(100), {limit_plus, false}});  // wire opens
  run(milliseconds(300));
  ASSERT_EQ(ctl->errors().active().size(), 1U);
  EXPECT_EQ(ctl->errors().active()[0].code_text(), "16");
}

TEST_F(ControllerRun, DeviceLogicRaisesWithTheCataloguesReaction) {
  make();
  ctl->raise_drive_off = true;
  run(milliseconds(40));
  ASSERT_EQ(ctl->errors().active().size(), 1U);
  EXPECT_EQ(ctl->errors().active()[0].code_text(), "14");
  EXPECT_EQ(ax->status().state, motion::AxisState::disabled) << "drive_off disables the axis";
}

TEST(Controller, BindAxesChecksTheCount) {
  auto p = profiles::find_profile("wf725-726");
  ASSERT_TRUE(p);
  TestController ctl(*p);
  const auto r = ctl.bind_axes({});
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().find("declares 1 axes"), std::string::npos) << r.error();
  EXPECT_STREQ(controller_category().name(), "controller");
  EXPECT_EQ(make_error_code(ControllerFault::hard_limit_negative).message(), "negative limit switch reached");
}

}  // namespace
}  // namespace hil::controllers
