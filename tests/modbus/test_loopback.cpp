// SPDX-License-Identifier: MIT
// Our drive against our server over loopback TCP: enable, position and velocity following with
// both profiles (FC 23; FC 4 + FC 16 with low-word-first values and scaling), drive faults.
#include <cmath>
#include <thread>

#include "loopback_fixture.hpp"

namespace hil::test {
namespace {

using std::chrono::milliseconds;

TEST(ModbusLoopback, Cia402EnablesAndFollowsPositionWithFc23) {
  Loopback lb("cia402.yaml");
  lb.cycle();
  EXPECT_EQ(lb.fb().state, DriveState::switch_on_disabled);
  EXPECT_EQ(lb.fb().age, Duration{});  // lockstep: the image is from this cycle
  ASSERT_TRUE(lb.enable());
  // Ramp the target to 20000 increments over 200 ms, then hold.
  for (int i = 1; i <= 400; ++i) {
    lb.command.position_inc = std::min(i, 200) * 100;
    lb.cycle();
  }
  EXPECT_EQ(lb.fb().state, DriveState::operation_enabled);
  EXPECT_NEAR(static_cast<double>(lb.fb().position_inc), 20000.0, 5.0);
  EXPECT_TRUE(lb.fb().referenced);
  EXPECT_FALSE(lb.fb().fault);
  const double server_pos = lb.server->with_device([](mocks::DriveDevice& d) { return d.plant().position_inc(); });
  EXPECT_NEAR(server_pos, 20000.0, 5.0);
  const auto stats = lb.drive->link_stats();
  EXPECT_EQ(stats.connects, 1u);
  EXPECT_EQ(stats.errors, 0u);
  EXPECT_GE(stats.exchanges, 400u);
  EXPECT_EQ(lb.server->stats().requests, stats.exchanges);  // FC 23: one request per exchange
}

TEST(ModbusLoopback, VendorProfileVelocityModeLowWordFirstAndScale) {
  Loopback lb("vendor_simple.yaml");
  ASSERT_TRUE(lb.enable());
  lb.command.mode = CommandMode::velocity;
  lb.command.velocity_inc_per_s = -200000.0;  // register value -20000 at scale 10
  for (int i = 0; i < 300; ++i) lb.cycle();
  EXPECT_NEAR(lb.fb().velocity_inc_per_s, -200000.0, 20.0);
  EXPECT_LT(lb.fb().position_inc, -40000);
  // The raw registers hold the position low word first.
  const auto [lo, hi, pos] = lb.server->with_device([](mocks::DriveDevice& d) {
    return std::tuple{d.table().get(modbus::RegisterSpace::input, 1), d.table().get(modbus::RegisterSpace::input, 2),
                      d.plant().encoder_position_inc()};
  });
  const auto raw = static_cast<std::int32_t>((std::uint32_t{hi} << 16) | lo);
  EXPECT_NEAR(static_cast<double>(raw), static_cast<double>(pos), 200.0 * 1.0 + 1.0);  // plant moved since the read
  EXPECT_EQ(lb.server->stats().requests, 2 * lb.drive->link_stats().exchanges);        // FC 16 + FC 4
  // Disable: the drive leaves operation enabled and the axis coasts down.
  lb.drive->request(DriveRequest::disable);
  ASSERT_TRUE(lb.cycle_until([&] { return lb.fb().state == DriveState::switch_on_disabled; }, 10));
}

TEST(ModbusLoopback, QuickStopRampsDownToSwitchOnDisabled) {
  Loopback lb("cia402.yaml");
  ASSERT_TRUE(lb.enable());
  lb.command.mode = CommandMode::velocity;
  lb.command.velocity_inc_per_s = 100000.0;
  for (int i = 0; i < 100; ++i) lb.cycle();
  lb.drive->request(DriveRequest::quick_stop);
  ASSERT_TRUE(lb.cycle_until([&] { return lb.fb().state == DriveState::quick_stop_active; }, 5));
  ASSERT_TRUE(lb.cycle_until([&] { return lb.fb().state == DriveState::switch_on_disabled; }, 100));
  EXPECT_LT(std::fabs(lb.fb().velocity_inc_per_s), 1000.0);
}

TEST(ModbusLoopback, PlantFaultShowsDriveFaultCodeAndResets) {
  Loopback lb("cia402.yaml");
  ASSERT_TRUE(lb.enable());
  lb.server->inject(PlantFault::encoder, true);
  ASSERT_TRUE(lb.cycle_until([&] { return lb.fb().state == DriveState::fault; }, 5));
  EXPECT_STREQ(lb.fb().fault.code.category().name(), "modbus-drive");
  EXPECT_EQ(lb.fb().fault.code.value(), 0x7305);
  EXPECT_NE(lb.fb().fault.text.find("encoder"), std::string::npos) << lb.fb().fault.text;
  // Reset while the cause is active: stays in fault.
  lb.drive->request(DriveRequest::fault_reset);
  for (int i = 0; i < 10; ++i) lb.cycle();
  EXPECT_EQ(lb.fb().state, DriveState::fault);
  lb.server->inject(PlantFault::encoder, false);
  lb.drive->request(DriveRequest::fault_reset);
  ASSERT_TRUE(lb.cycle_until([&] { return lb.fb().state == DriveState::switch_on_disabled; }, 10));
  EXPECT_FALSE(lb.fb().fault);
  ASSERT_TRUE(lb.enable());
}

TEST(ModbusLoopback, VendorFaultNumberAndText) {
  Loopback lb("vendor_simple.yaml");
  ASSERT_TRUE(lb.enable());
  lb.server->inject(PlantFault::following_blowup, true);
  ASSERT_TRUE(lb.cycle_until([&] { return lb.fb().state == DriveState::fault; }, 5));
  EXPECT_EQ(lb.fb().fault.code.value(), 3);
  EXPECT_NE(lb.fb().fault.text.find("jam"), std::string::npos) << lb.fb().fault.text;
  lb.server->inject(PlantFault::following_blowup, false);
  lb.drive->request(DriveRequest::fault_reset);
  ASSERT_TRUE(lb.cycle_until([&] { return lb.fb().state == DriveState::switch_on_disabled; }, 10));
}

// Real-time mode as `hilbridge run` uses it: the worker free-runs every poll period, the server
// steps its plant on its own timer, the motion thread only copies images. Waits are bounded.
TEST(ModbusLoopback, FreeRunningOnRealTime) {
  auto profile = shipped_profile("cia402.yaml");
  mocks::ModbusServerConfig sc;
  sc.auto_step = milliseconds(1);
  mocks::ModbusDriveServer server(mocks::DriveDevice(profile), sc);
  ASSERT_FALSE(server.start());
  SteadyClock clock;
  drives::ModbusDriveConfig c;
  c.profile = profile;
  c.port = server.port();
  c.poll_period = milliseconds(1);
  drives::ModbusDrive drive(c, clock);
  DriveCommand cmd;
  auto run_until = [&](auto pred) {
    const auto deadline = clock.now() + std::chrono::seconds(10);
    while (clock.now() < deadline) {
      const CycleTime t{clock.now(), milliseconds(1)};
      drive.read(t);
      drive.write(t, cmd);
      if (pred()) return true;
      std::this_thread::yield();
    }
    return false;
  };
  drive.request(DriveRequest::enable);
  ASSERT_TRUE(run_until([&] { return drive.feedback().state == DriveState::operation_enabled; }));
  cmd.position_inc = 1000;
  ASSERT_TRUE(run_until([&] { return std::abs(drive.feedback().position_inc - 1000) <= 2; }));
  EXPECT_LT(drive.feedback().age, std::chrono::milliseconds(500));  // fresh, not a frozen image
  EXPECT_GT(drive.link_stats().exchanges, 5u);
}

// A small drive with 16-bit registers only, written one register per request (FC 6), feedback
// read with FC 3, positions scaled 4 increments per register unit.
TEST(ModbusLoopback, Fc6ProfileWith16BitScaledValues) {
  auto profile = modbus::parse_profile(R"(name: tiny
state_machine: vendor
function_codes: {read: 3, write: 6}
bits: {enable: 0, fault_reset: 7, ready: 0, enabled: 1, fault: 3}
registers:
  control_word:    {address: 40}
  target_position: {address: 41, type: s16, scale: 4}
  status_word:     {address: 50}
  actual_position: {address: 51, type: s16, scale: 4}
)",
                                       "tiny.yaml");
  ASSERT_TRUE(profile) << profile.error().describe();
  mocks::ModbusDriveServer server(mocks::DriveDevice(*profile), {});
  ASSERT_FALSE(server.start());
  VirtualClock clock;
  drives::ModbusDriveConfig c;
  c.profile = *profile;
  c.port = server.port();
  c.lockstep = true;
  drives::ModbusDrive drive(c, clock);
  EXPECT_FALSE(drive.capabilities().velocity_mode);  // no mode / target velocity registers
  DriveCommand cmd;
  auto cycle = [&] {
    clock.advance(milliseconds(1));
    server.step(milliseconds(1));
    ASSERT_TRUE(drive.exchange_sync(clock.now()));
    drive.read({clock.now(), milliseconds(1)});
    drive.write({clock.now(), milliseconds(1)}, cmd);
  };
  drive.request(DriveRequest::enable);
  for (int i = 0; i < 5; ++i) cycle();
  ASSERT_EQ(drive.feedback().state, DriveState::operation_enabled);
  cmd.position_inc = -4000;  // register value -1000
  for (int i = 0; i < 400; ++i) cycle();
  EXPECT_EQ(drive.feedback().position_inc, -4000);
  const auto raw =
      server.with_device([](mocks::DriveDevice& d) { return d.table().get(modbus::RegisterSpace::holding, 41); });
  EXPECT_EQ(static_cast<std::int16_t>(raw), -1000);
  EXPECT_EQ(server.stats().requests, 3 * drive.link_stats().exchanges);  // 2 x FC 6 + 1 x FC 3
  EXPECT_EQ(drive.link_stats().errors, 0u);
}

TEST(ModbusLoopback, HomingOnTheCurrentPositionOverCia402Registers) {
  Loopback lb("cia402.yaml");
  ASSERT_TRUE(lb.drive->capabilities().homing);
  ASSERT_TRUE(lb.enable());
  for (int i = 1; i <= 400; ++i) {  // move to 5000 increments first, and settle
    lb.command.position_inc = std::min(i, 100) * 50;
    lb.cycle();
  }
  ASSERT_NEAR(static_cast<double>(lb.fb().position_inc), 5000.0, 5.0);
  ASSERT_TRUE(lb.drive->request(DriveRequest::home));
  lb.command.position_inc = lb.fb().position_inc;  // the axis holds while the drive homes
  lb.cycle();
  EXPECT_TRUE(lb.fb().homing_active);
  EXPECT_FALSE(lb.fb().referenced);
  std::int64_t mode_seen = 0;
  ASSERT_TRUE(lb.cycle_until(
      [&] {
        mode_seen = std::max<std::int64_t>(mode_seen, lb.server->with_device([](mocks::DriveDevice& d) {
          return static_cast<std::int64_t>(d.table().get(modbus::RegisterSpace::holding, 1));  // the mode register
        }));
        return !lb.fb().homing_active;
      },
      50));
  EXPECT_EQ(mode_seen, 6) << "the homing mode went over the wire";
  EXPECT_TRUE(lb.fb().referenced);
  EXPECT_EQ(lb.fb().position_inc, 0) << "homed on the current position: it is the reference point now";
  EXPECT_EQ(lb.fb().state, DriveState::operation_enabled);
  // Back in CSP, the axis moves from the new reference.
  for (int i = 1; i <= 300; ++i) {
    lb.command.position_inc = std::min(i, 100) * 10;
    lb.cycle();
  }
  EXPECT_NEAR(static_cast<double>(lb.fb().position_inc), 1000.0, 5.0);
  EXPECT_EQ(
      lb.server->with_device([](mocks::DriveDevice& d) { return d.table().get(modbus::RegisterSpace::holding, 1); }),
      8);
}

TEST(ModbusLoopback, HomingThatCannotRunEndsUnreferenced) {
  Loopback lb("cia402.yaml");
  lb.drive.reset();
  drives::ModbusDriveConfig c;
  c.port = lb.server->port();
  c.profile = lb.profile;
  c.lockstep = true;
  c.homing_timeout = std::chrono::milliseconds(50);
  lb.drive = std::make_unique<drives::ModbusDrive>(c, lb.clock);
  lb.cycle();
  ASSERT_TRUE(lb.drive->request(DriveRequest::home));  // not enabled: the drive cannot home
  ASSERT_TRUE(lb.cycle_until([&] { return !lb.fb().homing_active; }, 100));
  EXPECT_FALSE(lb.fb().referenced) << "timed out: not referenced, so the axis reports a failed homing";
}

TEST(ModbusLoopback, HomingIsRefusedNotFakedWithoutAHomingMode) {
  Loopback lb("vendor_simple.yaml");
  EXPECT_FALSE(lb.drive->capabilities().homing);
  EXPECT_FALSE(lb.drive->request(DriveRequest::home));
  EXPECT_TRUE(lb.drive->capabilities().velocity_mode);
}

}  // namespace
}  // namespace hil::test
