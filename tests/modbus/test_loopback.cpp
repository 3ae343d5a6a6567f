// SPDX-License-Identifier: MIT
// Our drive against our server over loopback TCP: enable, position and velocity following with
// both profiles (FC 23; FC 4 + FC 16 with low-word-first values and scaling), drive faults.
#include <cmath>

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
  EXPECT_EQ(lb.server->stats().requests, 2 * lb.drive->link_stats().exchanges);  // FC 16 + FC 4
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

TEST(ModbusLoopback, HomingIsRefusedNotFaked) {
  Loopback lb("cia402.yaml");
  EXPECT_FALSE(lb.drive->capabilities().homing);
  EXPECT_FALSE(lb.drive->request(DriveRequest::home));
  EXPECT_TRUE(lb.drive->capabilities().velocity_mode);
}

}  // namespace
}  // namespace hil::test
