// SPDX-License-Identifier: MIT
// The three operating setups of the CiA 402 drive, end to end on the virtual clock: a motion
// axis over Cia402Drive over our master, the virtual bus and a simulated node.
//  * pp: positioning moves in profile position with the set-point handshake (checked on the
//    wire: controlword bit 4 raised with bit 5, held until statusword bit 12, then dropped), a new
//    target while moving, velocity moves in profile velocity, stop as halt;
//  * csv: hilbridge closes the position loop over cyclic synchronous velocity.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

#include "hil/can/virtual_bus.hpp"
#include "hil/canopen/eds.hpp"
#include "hil/cia402/cia402.hpp"
#include "hil/cia402/cia402_drive.hpp"
#include "hil/cia402/layout.hpp"
#include "hil/mocks/cia402_node.hpp"
#include "hil/motion/axis.hpp"

using namespace std::chrono_literals;
namespace cia402 = hil::cia402;
using hil::motion::AxisState;

namespace {

constexpr hil::canopen::NodeId kNode = 3;

hil::motion::AxisConfig axis_config() {
  hil::motion::AxisConfig c;
  c.name = "x";
  c.inc_per_unit = {1000, 1};  // increments per mm
  c.limits = {100.0, 1000.0, std::numeric_limits<double>::infinity()};
  c.quick_stop_deceleration = 5000.0;
  c.jog_velocity = 20.0;
  c.following_error.static_window = 0.5;
  c.standstill_window = 0.05;
  c.in_position_window = 0.02;
  c.in_position_timeout = 300ms;
  c.feedback_timeout = 50ms;
  return c;
}

/// One axis on one simulated node; a monitor on the bus records RPDO1 (controlword) and TPDO1
/// (statusword) as they went over the wire.
struct Rig {
  hil::VirtualClock clock;
  hil::can::VirtualBus bus{clock, "vbus"};
  std::unique_ptr<hil::can::VirtualChannel> master_channel = bus.attach("master");
  std::unique_ptr<hil::can::VirtualChannel> node_channel = bus.attach("node");
  std::unique_ptr<hil::can::VirtualChannel> monitor = bus.attach("monitor");
  std::unique_ptr<cia402::Network> network;
  std::unique_ptr<hil::mocks::Cia402Node> node;
  std::unique_ptr<hil::motion::Axis> axis;
  std::vector<std::uint16_t> controlwords, statuswords;

  explicit Rig(cia402::OperatingSetup setup, hil::motion::AxisConfig config = axis_config()) {
    hil::canopen::MasterOptions mo;
    mo.sync_period = 1ms;
    network = std::make_unique<cia402::Network>(*master_channel, mo);
    node = std::make_unique<hil::mocks::Cia402Node>(*node_channel, hil::mocks::Cia402NodeOptions{.node = kNode});
    auto eds = hil::canopen::parse_eds(hil::mocks::cia402_node_eds(), "eds", kNode);
    EXPECT_TRUE(eds);
    cia402::AxisOptions ao;
    ao.node = kNode;
    ao.setup = setup;
    network->master().add_node(cia402::make_axis_node_config(*eds, ao));
    cia402::DriveOptions dopt;
    dopt.setup = setup;
    axis = std::make_unique<hil::motion::Axis>(config, std::make_unique<cia402::Cia402Drive>(*network, kNode, dopt));
    monitor->set_receive_handler([this](const hil::can::Frame& f, hil::TimePoint) {
      const auto word = static_cast<std::uint16_t>(f.data[0] | (f.data[1] << 8));
      if (f.id == 0x200u + kNode) controlwords.push_back(word);
      if (f.id == 0x180u + kNode) statuswords.push_back(word);
    });
    node->start(clock.now());
    network->start(clock.now());
    bus.deliver(clock.now());
  }
  void cycle() {
    clock.advance(1ms);
    const hil::CycleTime c{clock.now(), 1ms};
    network->step(c.now);
    bus.deliver(c.now);
    axis->update(c);
    node->step(c.now);
    bus.deliver(c.now);
  }
  bool run_until(const std::function<bool()>& done, hil::Duration limit) {
    for (auto end = clock.now() + limit; clock.now() < end;) {
      cycle();
      if (done()) return true;
    }
    return false;
  }
  void enable() {
    ASSERT_TRUE(run_until([&] { return axis->status().drive_state == hil::DriveState::switch_on_disabled; }, 500ms));
    ASSERT_FALSE(axis->enable());
    ASSERT_TRUE(run_until([&] { return axis->status().state == AxisState::standstill; }, 200ms))
        << axis->status().fault.describe();
  }
  bool at_rest() const {
    const auto& s = axis->status();
    return s.state == AxisState::standstill && !s.busy && s.in_position;
  }
  std::int8_t node_mode() const { return static_cast<std::int8_t>(node->od().get_int(0x6061, 0)); }
};

TEST(Cia402ProfilePosition, MoveWithTheSetPointHandshakeOnTheWire) {
  Rig rig(cia402::OperatingSetup::pp);
  rig.enable();
  rig.run_until([] { return false; }, 5ms);  // the controlword of an enabled cycle is on the wire
  EXPECT_TRUE(rig.controlwords.back() & cia402::cw::halt) << "enabled and holding: halt";
  rig.controlwords.clear();
  rig.statuswords.clear();

  ASSERT_FALSE(rig.axis->move_absolute(50.0));
  ASSERT_TRUE(rig.run_until([&] { return rig.at_rest(); }, 2s)) << rig.axis->status().fault.describe();
  EXPECT_EQ(rig.node_mode(), 1) << "profile position";
  EXPECT_NEAR(rig.axis->status().position, 50.0, 0.02);
  EXPECT_EQ(rig.node->od().get_int(0x607A, 0), 50'000);
  EXPECT_EQ(rig.node->od().get_int(0x6081, 0), 100'000) << "profile velocity in increments/s";
  EXPECT_EQ(rig.node->od().get_int(0x6083, 0), 1'000'000);

  // The handshake: bit 4 rises (with bit 5, no halt), stays up until the node's bit 12, then falls.
  std::size_t raised = 0;
  while (raised < rig.controlwords.size() && !(rig.controlwords[raised] & cia402::cw::new_set_point)) ++raised;
  ASSERT_LT(raised, rig.controlwords.size()) << "no new set-point on the wire";
  EXPECT_TRUE(rig.controlwords[raised] & cia402::cw::change_immediately);
  EXPECT_FALSE(rig.controlwords[raised] & cia402::cw::halt);
  std::size_t dropped = raised;
  while (dropped < rig.controlwords.size() && (rig.controlwords[dropped] & cia402::cw::new_set_point)) ++dropped;
  ASSERT_LT(dropped, rig.controlwords.size()) << "bit 4 never dropped";
  const bool acknowledged = std::any_of(rig.statuswords.begin(), rig.statuswords.end(),
                                        [](std::uint16_t s) { return (s & cia402::sw::op_specific_12) != 0; });
  EXPECT_TRUE(acknowledged) << "the node acknowledged the set-point (statusword bit 12)";
  const auto rises = std::count_if(
      rig.controlwords.begin() + 1, rig.controlwords.end(), [&, i = std::size_t{0}](std::uint16_t cw) mutable {
        return (cw & cia402::cw::new_set_point) && !(rig.controlwords[i++] & cia402::cw::new_set_point);
      });
  EXPECT_EQ(rises + ((rig.controlwords.front() & cia402::cw::new_set_point) ? 1 : 0), 1) << "one move, one set-point";
  EXPECT_TRUE(rig.statuswords.back() & cia402::sw::target_reached);
}

TEST(Cia402ProfilePosition, NewTargetWhileMovingReplacesTheRunningOne) {
  Rig rig(cia402::OperatingSetup::pp);
  rig.enable();
  ASSERT_FALSE(rig.axis->move_absolute(80.0));
  rig.run_until([] { return false; }, 300ms);
  ASSERT_GT(rig.axis->status().position, 5.0) << "under way";
  ASSERT_LT(rig.axis->status().position, 60.0);
  ASSERT_FALSE(rig.axis->move_absolute(-20.0));
  ASSERT_TRUE(rig.run_until([&] { return rig.at_rest(); }, 3s)) << rig.axis->status().fault.describe();
  EXPECT_NEAR(rig.axis->status().position, -20.0, 0.02);
  EXPECT_LT(rig.node->plant().position_inc(), 0.0) << "the node went back, it did not finish the first move";
}

TEST(Cia402ProfileVelocity, VelocityMoveThenStopWithHalt) {
  Rig rig(cia402::OperatingSetup::pp);
  rig.enable();
  ASSERT_FALSE(rig.axis->move_velocity(-40.0));
  rig.run_until([] { return false; }, 400ms);
  EXPECT_EQ(rig.node_mode(), 3) << "profile velocity";
  EXPECT_NEAR(rig.axis->status().velocity, -40.0, 1.0);
  EXPECT_EQ(rig.node->od().get_int(0x60FF, 0), -40'000);
  ASSERT_FALSE(rig.axis->stop());
  ASSERT_TRUE(
      rig.run_until([&] { return rig.axis->status().state == AxisState::standstill && !rig.axis->status().busy; }, 1s))
      << rig.axis->status().fault.describe();
  rig.run_until([] { return false; }, 100ms);
  EXPECT_TRUE(rig.controlwords.back() & cia402::cw::halt);
  EXPECT_NEAR(rig.axis->status().velocity, 0.0, 0.01);
  EXPECT_EQ(rig.axis->status().state, AxisState::standstill) << rig.axis->status().fault.describe();
  EXPECT_EQ(rig.node_mode(), 3) << "halt keeps the mode that moved";
}

TEST(Cia402CyclicVelocity, HilbridgeClosesThePositionLoop) {
  Rig rig(cia402::OperatingSetup::csv);
  rig.enable();
  ASSERT_FALSE(rig.axis->move_absolute(25.0));
  ASSERT_TRUE(rig.run_until([&] { return rig.at_rest(); }, 2s)) << rig.axis->status().fault.describe();
  EXPECT_EQ(rig.node_mode(), 9) << "cyclic synchronous velocity";
  EXPECT_NEAR(rig.axis->status().position, 25.0, 0.02);
  rig.run_until([] { return false; }, 200ms);
  EXPECT_EQ(rig.axis->status().state, AxisState::standstill) << rig.axis->status().fault.describe();
  EXPECT_NEAR(rig.axis->status().position, 25.0, 0.02) << "the loop holds the position";
}

TEST(Cia402CyclicPosition, FollowingErrorIsSupervisedOnThePathInCspButNotInPp) {
  // The same too-tight window: CSP trips on the path, PP leaves the path to the drive.
  auto tight = axis_config();
  tight.following_error.static_window = 0.001;
  Rig csp(cia402::OperatingSetup::csp, tight);
  csp.enable();
  ASSERT_FALSE(csp.axis->move_absolute(50.0));
  csp.run_until([&] { return csp.axis->status().state == AxisState::error; }, 2s);
  EXPECT_EQ(csp.axis->status().fault.code, make_error_code(hil::MotionFault::following_error));

  Rig pp(cia402::OperatingSetup::pp, tight);
  pp.enable();
  ASSERT_FALSE(pp.axis->move_absolute(50.0));
  ASSERT_TRUE(pp.run_until([&] { return pp.at_rest(); }, 2s)) << pp.axis->status().fault.describe();
}

}  // namespace
