// SPDX-License-Identifier: MIT
// End to end on the virtual clock and the in-process virtual CAN bus: our master boots eight
// simulated CiA 402 nodes (identity check, configuration download with PDO remapping, start),
// runs CSP moves at 1 ms SYNC, recovers from drive faults, faults the axis on heartbeat loss
// within the consumer time, and reports frame loss and SDO timeouts with the right errors.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

#include "hil/can/virtual_bus.hpp"
#include "hil/canopen/eds.hpp"
#include "hil/cia402/cia402_drive.hpp"
#include "hil/cia402/error_code.hpp"
#include "hil/cia402/layout.hpp"
#include "hil/mocks/cia402_node.hpp"

using namespace std::chrono_literals;
using hil::DriveRequest;
using hil::DriveState;

namespace {

struct Machine {
  hil::VirtualClock clock;
  hil::can::VirtualBus bus{clock, "vbus"};
  std::unique_ptr<hil::can::VirtualChannel> master_channel = bus.attach("master");
  std::unique_ptr<hil::cia402::Network> network;
  std::vector<std::unique_ptr<hil::can::VirtualChannel>> node_channels;
  std::vector<std::unique_ptr<hil::mocks::Cia402Node>> nodes;
  std::vector<std::unique_ptr<hil::cia402::Cia402Drive>> drives;
  hil::CycleTime cycle{};
  std::vector<hil::DriveCommand> commands;
  std::function<void()> before_write;  ///< the motion core's part of a cycle

  explicit Machine(int count, hil::cia402::AxisOptions axis = {},
                   std::function<void(hil::canopen::NodeConfig&)> tweak = {}) {
    hil::canopen::MasterOptions mo;
    mo.sync_period = 1ms;
    mo.sdo.timeout = 20ms;
    mo.boot_timeout = 100ms;
    mo.boot_retries = 1;
    network = std::make_unique<hil::cia402::Network>(*master_channel, mo);
    for (int i = 0; i < count; ++i) {
      const auto id = static_cast<hil::canopen::NodeId>(i + 1);
      node_channels.push_back(bus.attach("node" + std::to_string(id)));
      hil::mocks::Cia402NodeOptions no;
      no.node = id;
      nodes.push_back(std::make_unique<hil::mocks::Cia402Node>(*node_channels.back(), no));
      auto eds = hil::canopen::parse_eds(hil::mocks::cia402_node_eds(), "eds", id);
      EXPECT_TRUE(eds);
      axis.node = id;
      auto cfg = hil::cia402::make_axis_node_config(*eds, axis);
      if (tweak) tweak(cfg);
      network->master().add_node(std::move(cfg));
      drives.push_back(std::make_unique<hil::cia402::Cia402Drive>(*network, id, hil::cia402::DriveOptions{}));
      commands.emplace_back();
    }
  }
  void power_on() {
    for (auto& n : nodes) n->start(clock.now());
    network->start(clock.now());
    bus.deliver(clock.now());
  }
  void cycle_once() {
    clock.advance(1ms);
    cycle.now = clock.now();
    network->step(cycle.now);
    bus.deliver(cycle.now);
    for (std::size_t i = 0; i < drives.size(); ++i) drives[i]->read(cycle);
    if (before_write) before_write();
    for (std::size_t i = 0; i < drives.size(); ++i) drives[i]->write(cycle, commands[i]);
    for (auto& n : nodes) n->step(cycle.now);
    bus.deliver(cycle.now);
  }
  void run(hil::Duration d) {
    for (auto end = clock.now() + d; clock.now() < end;) cycle_once();
  }
  bool run_until(const std::function<bool()>& pred, hil::Duration limit) {
    for (auto end = clock.now() + limit; clock.now() < end;) {
      cycle_once();
      if (pred()) return true;
    }
    return false;
  }
  bool all_in(DriveState s) const {
    for (const auto& d : drives)
      if (d->feedback().state != s) return false;
    return true;
  }
};

}  // namespace

TEST(CanopenEndToEnd, EightNodesBootMoveInCspAndRecoverFromAFault) {
  Machine m(8);
  m.power_on();
  ASSERT_TRUE(m.run_until([&] { return m.all_in(DriveState::switch_on_disabled); }, 500ms));
  for (auto id : m.network->master().nodes()) {
    EXPECT_EQ(m.network->master().status(id).boot, hil::canopen::NodeBootState::started);
    EXPECT_EQ(m.nodes[id - 1u]->nmt_state(), hil::canopen::NmtState::operational);
    EXPECT_EQ(m.nodes[id - 1u]->od().get_int(0x1A00, 3), 0x603F0010) << "the remap reached the node";
  }
  for (auto& d : m.drives) d->request(DriveRequest::enable);
  ASSERT_TRUE(m.run_until([&] { return m.all_in(DriveState::operation_enabled); }, 100ms));

  // CSP: every axis follows a 200 ms ramp to its own target at 1 ms SYNC.
  for (int k = 1; k <= 200; ++k) {
    for (std::size_t i = 0; i < m.drives.size(); ++i) {
      m.commands[i].position_inc = static_cast<std::int64_t>(k * 50 * static_cast<int>(i + 1));
      m.commands[i].velocity_inc_per_s = 50'000.0 * static_cast<double>(i + 1);
    }
    m.cycle_once();
  }
  m.run(300ms);
  for (std::size_t i = 0; i < m.drives.size(); ++i) {
    const auto target = 10'000.0 * static_cast<double>(i + 1);
    EXPECT_NEAR(static_cast<double>(m.drives[i]->feedback().position_inc), target, 50.0) << "axis " << i + 1;
    EXPECT_NEAR(m.nodes[i]->plant().position_inc(), target, 50.0);
    EXPECT_LT(m.drives[i]->feedback().age, 3ms);
  }

  // Fault on node 3: the axis reports the CiA 402 code, the others keep running.
  m.nodes[2]->inject_fault("overcurrent", true, m.clock.now());
  ASSERT_TRUE(m.run_until([&] { return m.drives[2]->feedback().state == DriveState::fault; }, 100ms));
  const auto& fault = m.drives[2]->feedback().fault;
  EXPECT_EQ(fault.code, hil::cia402::ErrorCode::continuous_over_current);
  EXPECT_STREQ(fault.code.category().name(), "cia402");
  EXPECT_NE(fault.text.find("Continuous over-current"), std::string::npos) << fault.text;
  EXPECT_EQ(m.drives[3]->feedback().state, DriveState::operation_enabled);
  m.drives[2]->request(DriveRequest::fault_reset);
  m.run(5ms);
  EXPECT_EQ(m.drives[2]->feedback().state, DriveState::not_ready) << "reset acknowledged, not yet confirmed";
  m.run(250ms);
  EXPECT_EQ(m.drives[2]->feedback().state, DriveState::fault) << "reset is refused while the cause persists";
  EXPECT_NE(m.drives[2]->feedback().fault.text.find("refused"), std::string::npos);
  m.nodes[2]->inject_fault("overcurrent", false, m.clock.now());
  m.drives[2]->request(DriveRequest::fault_reset);
  ASSERT_TRUE(m.run_until([&] { return m.drives[2]->feedback().state == DriveState::switch_on_disabled; }, 50ms));
  EXPECT_FALSE(m.drives[2]->feedback().fault);
  m.drives[2]->request(DriveRequest::enable);
  ASSERT_TRUE(m.run_until([&] { return m.drives[2]->feedback().state == DriveState::operation_enabled; }, 50ms));
}

TEST(CanopenEndToEnd, HeartbeatLossFaultsTheAxisWithinTheConsumerTime) {
  hil::cia402::AxisOptions axis;
  axis.heartbeat_producer = 20ms;
  axis.heartbeat_consumer = 50ms;
  Machine m(2, axis);
  m.power_on();
  ASSERT_TRUE(m.run_until([&] { return m.all_in(DriveState::switch_on_disabled); }, 500ms));
  for (auto& d : m.drives) d->request(DriveRequest::enable);
  ASSERT_TRUE(m.run_until([&] { return m.all_in(DriveState::operation_enabled); }, 100ms));
  m.run(100ms);
  // Find the last heartbeat before the loss: the fault must come at most 50 ms (+1 cycle) after it.
  hil::TimePoint last_hb{};
  auto* tap = m.bus.attach("tap").release();
  tap->set_receive_handler([&](const hil::can::Frame& f, hil::TimePoint t) {
    if (f.id == 0x702) last_hb = t;
  });
  m.run(25ms);
  m.nodes[1]->inject_fault("heartbeat_loss", true, m.clock.now());
  ASSERT_TRUE(m.run_until([&] { return m.drives[1]->feedback().state == DriveState::fault; }, 200ms));
  const auto detected = m.clock.now();
  EXPECT_LE(detected - last_hb, 51ms);
  EXPECT_GT(detected - last_hb, 49ms);
  EXPECT_EQ(m.drives[1]->feedback().fault.code, hil::cia402::ErrorCode::heartbeat);
  EXPECT_EQ(m.drives[0]->feedback().state, DriveState::operation_enabled);
  EXPECT_EQ(m.drives[1]->controlword(), 0x0000) << "the master disables a drive it cannot supervise";
  delete tap;
}

TEST(CanopenEndToEnd, LostProcessDataMakesTheFeedbackStale) {
  Machine m(1);
  m.power_on();
  ASSERT_TRUE(m.run_until([&] { return m.all_in(DriveState::switch_on_disabled); }, 500ms));
  m.drives[0]->request(DriveRequest::enable);
  ASSERT_TRUE(m.run_until([&] { return m.all_in(DriveState::operation_enabled); }, 100ms));
  hil::can::FrameFault drop;
  drop.action = hil::can::FaultAction::drop;
  // Every TPDO of the node (TPDO3 carries the digital inputs 0x60FD).
  drop.match = [](const hil::can::Frame& f) { return f.id == 0x181 || f.id == 0x281 || f.id == 0x381; };
  m.bus.inject(drop);
  ASSERT_TRUE(m.run_until([&] { return m.drives[0]->feedback().state == DriveState::fault; }, 200ms));
  EXPECT_EQ(m.drives[0]->feedback().fault.code, hil::MotionFault::drive_lost);
  EXPECT_GE(m.drives[0]->feedback().age, 50ms);
}

TEST(CanopenEndToEnd, SdoTimeoutDuringBootIsReported) {
  Machine m(2);
  m.nodes[1]->inject_fault("sdo_timeout", true, m.clock.now());
  m.power_on();
  m.run(300ms);
  const auto& st = m.network->master().status(2);
  EXPECT_EQ(st.boot, hil::canopen::NodeBootState::failed);
  EXPECT_EQ(st.boot_error, hil::canopen::BootError::no_response);
  EXPECT_NE(st.detail.find("0x05040000"), std::string::npos) << st.detail;
  EXPECT_EQ(m.drives[1]->feedback().state, DriveState::not_ready);
  EXPECT_EQ(m.drives[1]->feedback().fault.code, hil::canopen::BootError::no_response);
  EXPECT_EQ(m.network->master().status(1).boot, hil::canopen::NodeBootState::started);
}

TEST(CanopenEndToEnd, IdentityMismatchStopsTheBoot) {
  Machine m(1, {}, [](hil::canopen::NodeConfig& c) { c.product_code = 0x1234; });
  m.power_on();
  m.run(100ms);
  const auto& st = m.network->master().status(1);
  EXPECT_EQ(st.boot_error, hil::canopen::BootError::product_code);
  EXPECT_NE(st.detail.find("0x00000402"), std::string::npos) << st.detail;
  EXPECT_EQ(m.nodes[0]->nmt_state(), hil::canopen::NmtState::preoperational) << "never started";
}

TEST(CanopenEndToEnd, MissingNodeTimesOutWaitingForBootUp) {
  Machine m(1);
  m.network->start(m.clock.now());  // the node is never powered
  m.run(300ms);
  EXPECT_EQ(m.network->master().status(1).boot_error, hil::canopen::BootError::no_response);
  EXPECT_NE(m.network->master().status(1).detail.find("no boot-up"), std::string::npos);
}

TEST(CanopenEndToEnd, HomingOnCurrentPosition) {
  Machine m(1);
  m.power_on();
  ASSERT_TRUE(m.run_until([&] { return m.all_in(DriveState::switch_on_disabled); }, 500ms));
  m.nodes[0]->od().set_int(0x607C, 0, 5000);  // home offset
  m.drives[0]->request(DriveRequest::enable);
  ASSERT_TRUE(m.run_until([&] { return m.all_in(DriveState::operation_enabled); }, 100ms));
  // As the motion core does: hold the command at the feedback while homing runs.
  bool was_homing = false;
  m.before_write = [&] {
    if (m.drives[0]->feedback().homing_active || was_homing)
      m.commands[0].position_inc = m.drives[0]->feedback().position_inc;
    was_homing = m.drives[0]->feedback().homing_active;
  };
  ASSERT_TRUE(m.drives[0]->request(DriveRequest::home));
  EXPECT_TRUE(m.drives[0]->feedback().homing_active);
  ASSERT_TRUE(m.run_until([&] { return m.drives[0]->feedback().referenced; }, 100ms));
  EXPECT_FALSE(m.drives[0]->feedback().homing_active);
  m.run(5ms);
  EXPECT_NEAR(static_cast<double>(m.drives[0]->feedback().position_inc), 5000.0, 2.0);
  EXPECT_EQ(m.drives[0]->feedback().state, DriveState::operation_enabled);
}
