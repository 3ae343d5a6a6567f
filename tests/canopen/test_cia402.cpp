// SPDX-License-Identifier: MIT
// CiA 402-2 power state machine: statusword decoding (including a real drive's log), every
// device-side transition from the controlword table, the master's walk toward a goal, the
// fault-reset rising edge, and the error-code table / category. Plus PP, PV and quick stop on
// the simulated node driven frame by frame.
#include <gtest/gtest.h>

#include "hil/can/virtual_bus.hpp"
#include "hil/cia402/cia402.hpp"
#include "hil/cia402/error_code.hpp"
#include "hil/mocks/cia402_node.hpp"

using namespace hil::cia402;
using hil::DriveState;
using namespace std::chrono_literals;

TEST(Cia402, StatuswordDecodingTable) {
  struct Row {
    std::uint16_t sw;
    DriveState state;
  };
  const Row rows[] = {
      {0x0000, DriveState::not_ready},
      {0x0040, DriveState::switch_on_disabled},
      {0x0250, DriveState::switch_on_disabled},
      {0x0021, DriveState::ready_to_switch_on},
      {0x0231, DriveState::ready_to_switch_on},
      {0x0023, DriveState::switched_on},
      {0x0233, DriveState::switched_on},
      {0x0027, DriveState::operation_enabled},
      {0x0637, DriveState::operation_enabled},
      {0x0007, DriveState::quick_stop_active},
      {0x1617, DriveState::quick_stop_active},   // real drive log: bit 5 clear with bits 0-2 set
      {0x0640, DriveState::switch_on_disabled},  // real drive log: 181#4006
      {0x000F, DriveState::fault_reaction_active},
      {0x002F, DriveState::fault_reaction_active},
      {0x0008, DriveState::fault},
      {0x0228, DriveState::fault},
  };
  for (const auto& r : rows) EXPECT_EQ(decode_state(r.sw), r.state) << std::hex << r.sw;
  for (auto s : {DriveState::not_ready, DriveState::switch_on_disabled, DriveState::ready_to_switch_on,
                 DriveState::switched_on, DriveState::operation_enabled, DriveState::quick_stop_active,
                 DriveState::fault_reaction_active, DriveState::fault})
    EXPECT_EQ(decode_state(encode_state(s)), s);
}

TEST(Cia402, DeviceTransitionsFromTheControlwordTable) {
  using S = DriveState;
  struct Row {
    S from;
    std::uint16_t cw;
    S to;
    const char* transition;
  };
  const Row rows[] = {
      {S::switch_on_disabled, 0x0006, S::ready_to_switch_on, "2 shutdown"},
      {S::switch_on_disabled, 0x0007, S::switch_on_disabled, "switch on is not a command here"},
      {S::switch_on_disabled, 0x0086, S::switch_on_disabled, "bit 7 set: fault reset, not shutdown"},
      {S::ready_to_switch_on, 0x0007, S::switched_on, "3 switch on"},
      {S::ready_to_switch_on, 0x000F, S::operation_enabled, "3+4 switch on + enable operation"},
      {S::ready_to_switch_on, 0x0000, S::switch_on_disabled, "7 disable voltage"},
      {S::ready_to_switch_on, 0x0002, S::switch_on_disabled, "7 quick stop"},
      {S::switched_on, 0x000F, S::operation_enabled, "4 enable operation"},
      {S::switched_on, 0x0006, S::ready_to_switch_on, "6 shutdown"},
      {S::switched_on, 0x0000, S::switch_on_disabled, "10 disable voltage"},
      {S::switched_on, 0x000B, S::switch_on_disabled, "10 quick stop (bit 2 low)"},
      {S::operation_enabled, 0x0007, S::switched_on, "5 disable operation"},
      {S::operation_enabled, 0x0006, S::ready_to_switch_on, "8 shutdown"},
      {S::operation_enabled, 0x0000, S::switch_on_disabled, "9 disable voltage"},
      {S::operation_enabled, 0x0002, S::quick_stop_active, "11 quick stop"},
      {S::operation_enabled, 0x001F, S::operation_enabled, "mode bits do not change the state"},
      {S::quick_stop_active, 0x0000, S::switch_on_disabled, "12 disable voltage"},
      {S::quick_stop_active, 0x000F, S::quick_stop_active, "16 only with option codes 5..8"},
      {S::fault, 0x0000, S::fault, "no edge, no reset"},
  };
  for (const auto& r : rows) EXPECT_EQ(next_state(r.from, r.cw, false, false), r.to) << r.transition;
  EXPECT_EQ(next_state(S::quick_stop_active, 0x000F, false, true), S::operation_enabled) << "16";
  EXPECT_EQ(next_state(S::fault, 0x0080, true, false), S::switch_on_disabled) << "15 on the rising edge";
  EXPECT_EQ(next_state(S::fault, 0x0080, false, false), S::fault) << "bit 7 held high is not an edge";
}

TEST(Cia402, MasterWalksTowardItsGoal) {
  using S = DriveState;
  // Device and master in a closed loop: the master's controlword drives the device's table. A
  // fault reset is sent only while `reset` is requested.
  auto walk = [](S start, S goal, bool reset) {
    S s = start;
    std::uint16_t cw = 0;
    for (int i = 0; i < 10 && s != goal; ++i) {
      const auto next_cw = reset && s == S::fault ? fault_reset_controlword(cw) : controlword_toward(s, goal);
      const bool edge = (next_cw & 0x80) && !(cw & 0x80);
      cw = next_cw;
      s = next_state(s, cw, edge, false);
    }
    return s;
  };
  for (auto start : {S::switch_on_disabled, S::ready_to_switch_on, S::switched_on, S::quick_stop_active}) {
    EXPECT_EQ(walk(start, S::operation_enabled, false), S::operation_enabled) << hil::to_string(start);
    EXPECT_EQ(walk(start, S::switch_on_disabled, false), S::switch_on_disabled) << hil::to_string(start);
  }
  EXPECT_EQ(walk(S::operation_enabled, S::quick_stop_active, false), S::quick_stop_active);
  // A fault stays latched whatever the goal until a reset is requested.
  for (auto goal : {S::operation_enabled, S::switch_on_disabled, S::quick_stop_active}) {
    EXPECT_EQ(walk(S::fault, goal, false), S::fault) << hil::to_string(goal);
    EXPECT_EQ(controlword_toward(S::fault, goal), 0x0000) << "disable voltage, never bit 7";
    EXPECT_EQ(controlword_toward(S::fault_reaction_active, goal), 0x0000);
  }
  EXPECT_EQ(walk(S::fault, S::switch_on_disabled, true), S::switch_on_disabled) << "15 on the requested reset";
  EXPECT_EQ(fault_reset_controlword(0x0080), 0x0000) << "bit 7 low first";
  EXPECT_EQ(fault_reset_controlword(0x0000), 0x0080) << "then the rising edge";
}

TEST(Cia402, ErrorCodesAndCategory) {
  std::error_code ec = ErrorCode::sensor_1;
  EXPECT_EQ(ec.value(), 0x7305);
  EXPECT_STREQ(ec.category().name(), "cia402");
  EXPECT_EQ(ec.message(), "0x7305 Incremental sensor 1 fault");
  EXPECT_EQ(describe(0x8611), "Following error");
  EXPECT_EQ(describe(0x2399), "Current") << "falls back to the group";
  EXPECT_EQ(describe(0xFF42), "Device specific");
  EXPECT_EQ(error_register_for(0x3220), 0x05);
  EXPECT_EQ(error_register_for(0x8130), 0x11);
  EXPECT_EQ(error_register_for(0x8611), 0x21);
  EXPECT_EQ(*supported_mode_bit(Mode::cyclic_sync_velocity), 0x100u);
}

// ---------------------------------------------------------------------------------------------
// Profile modes on the simulated node, frame by frame (the node alone, the test is the master).

namespace {
struct NodeBench : ::testing::Test {
  hil::VirtualClock clock;
  hil::can::VirtualBus bus{clock};
  std::unique_ptr<hil::can::VirtualChannel> me = bus.attach("test");
  std::unique_ptr<hil::can::VirtualChannel> ch = bus.attach("node");
  hil::mocks::Cia402Node node{*ch, {.node = 1}};
  void SetUp() override {
    me->set_receive_handler([](const hil::can::Frame&, hil::TimePoint) {});
    node.start(clock.now());
    send({0x01, 0x01}, 0x000);  // NMT start
  }
  void send(std::initializer_list<std::uint8_t> b, std::uint32_t id) {
    (void)me->send(hil::can::make_frame(id, b));
    bus.deliver(clock.now());
  }
  void sdo_write(std::uint16_t idx, std::uint8_t sub, std::int32_t v, std::uint8_t cs = 0x23) {
    send({cs, static_cast<std::uint8_t>(idx), static_cast<std::uint8_t>(idx >> 8), sub, static_cast<std::uint8_t>(v),
          static_cast<std::uint8_t>(v >> 8), static_cast<std::uint8_t>(v >> 16), static_cast<std::uint8_t>(v >> 24)},
         0x601);
  }
  void cw(std::uint16_t c) { node.od().set_int(0x6040, 0, c); }
  void run(hil::Duration d) {
    for (auto end = clock.now() + d; clock.now() < end;) {
      clock.advance(1ms);
      node.step(clock.now());
      bus.deliver(clock.now());
    }
  }
  std::uint16_t sw() { return static_cast<std::uint16_t>(node.od().get_int(0x6041, 0)); }
  void enable(std::int8_t mode) {
    sdo_write(0x6060, 0, mode, 0x2F);
    for (int c : {0x06, 0x07, 0x0F}) {
      cw(static_cast<std::uint16_t>(c));
      run(1ms);
    }
    ASSERT_EQ(node.state(), DriveState::operation_enabled);
  }
};
}  // namespace

TEST_F(NodeBench, ProfilePositionHandshakeAndTargetReached) {
  enable(1);
  sdo_write(0x607A, 0, 20000);
  cw(0x001F);  // new set-point
  run(1ms);
  EXPECT_TRUE(sw() & sw::op_specific_12) << "set-point acknowledge";
  EXPECT_FALSE(sw() & sw::target_reached);
  cw(0x000F);
  run(1ms);
  EXPECT_FALSE(sw() & sw::op_specific_12) << "acknowledge follows bit 4 down";
  run(1s);
  EXPECT_TRUE(sw() & sw::target_reached);
  EXPECT_NEAR(node.plant().position_inc(), 20000.0, 100.0);
  EXPECT_EQ(node.od().get_int(0x6061, 0), 1);
}

TEST_F(NodeBench, ProfileVelocityRampsAndQuickStopStops) {
  enable(3);
  sdo_write(0x60FF, 0, 50000);
  run(200ms);
  EXPECT_NEAR(node.plant().velocity_inc_per_s(), 50000.0, 1000.0);
  EXPECT_TRUE(sw() & sw::target_reached);
  cw(0x000B);  // quick stop
  run(1ms);
  EXPECT_EQ(node.state(), DriveState::quick_stop_active);
  EXPECT_FALSE(sw() & sw::quick_stop) << "bit 5 low while quick stop is active";
  run(100ms);
  EXPECT_EQ(node.state(), DriveState::switch_on_disabled) << "option code 2: stop, then switch on disabled";
  EXPECT_NEAR(node.plant().velocity_inc_per_s(), 0.0, 100.0);
}

TEST_F(NodeBench, EncoderFaultRaisesEmcyAndFaultResetNeedsAnEdge) {
  std::vector<hil::can::Frame> emcy;
  me->set_receive_handler([&](const hil::can::Frame& f, hil::TimePoint) {
    if (f.id == 0x081) emcy.push_back(f);
  });
  enable(8);
  node.inject_fault("encoder", true, clock.now());
  run(50ms);
  EXPECT_EQ(node.state(), DriveState::fault);
  EXPECT_EQ(node.od().get_int(0x603F, 0), 0x7305);
  ASSERT_EQ(emcy.size(), 1u);
  EXPECT_EQ(emcy[0].data[0], 0x05);
  EXPECT_EQ(emcy[0].data[1], 0x73);
  EXPECT_EQ(emcy[0].data[2], 0x01) << "error register: generic";
  node.inject_fault("encoder", false, clock.now());
  cw(0x0080);
  run(1ms);
  EXPECT_EQ(node.state(), DriveState::switch_on_disabled);
  ASSERT_EQ(emcy.size(), 2u);
  EXPECT_EQ(emcy[1].data[0], 0x00) << "error reset EMCY";
  EXPECT_EQ(node.od().get_int(0x603F, 0), 0);
}

TEST_F(NodeBench, FollowingErrorInjectionFaultsWith8611) {
  enable(8);
  node.inject_fault("following_error", true, clock.now());
  run(30ms);
  EXPECT_EQ(node.od().get_int(0x603F, 0), 0x8611);
}

TEST_F(NodeBench, FaultInjectionOverSdoObjects) {
  enable(8);
  sdo_write(0x2100, 0, 0x4310, 0x2B);
  run(30ms);
  EXPECT_EQ(node.state(), DriveState::fault);
  EXPECT_EQ(node.od().get_int(0x603F, 0), 0x4310);
}

TEST_F(NodeBench, LosingTheMastersHeartbeatStopsTheDrive) {
  sdo_write(0x1016, 1, 0x007F0032);  // monitor node 127 (the master), 50 ms
  send({0x05}, 0x77F);
  enable(8);
  for (int i = 0; i < 10; ++i) {
    send({0x05}, 0x77F);
    run(20ms);
  }
  EXPECT_EQ(node.state(), DriveState::operation_enabled) << "heartbeats keep coming";
  run(60ms);
  EXPECT_NE(node.state(), DriveState::operation_enabled);
  run(30ms);
  EXPECT_EQ(node.state(), DriveState::fault);
  EXPECT_EQ(node.od().get_int(0x603F, 0), 0x8130);
  EXPECT_EQ(node.od().get_int(0x1003, 1) & 0xFFFF, 0x8130) << "the EMCY went into the error history";
}
