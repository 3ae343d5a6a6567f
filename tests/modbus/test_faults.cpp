// SPDX-License-Identifier: MIT
// Fault tests, both ends real: exception responses, responses slower than the timeout, the
// server killed and restarted mid-run, malformed MBAP headers and wrong lengths from other
// clients, several clients at once, writes to read-only registers through libmodbus.
#include <modbus.h>

#include <cerrno>
#include <thread>

#include "loopback_fixture.hpp"
#include "raw_socket.hpp"

namespace hil::test {
namespace {

using std::chrono::milliseconds;

bool is_link_fault(const DriveFeedback& fb, modbus::ModbusError e) {
  return fb.state == DriveState::fault && fb.fault.code == modbus::make_error_code(e);
}

TEST(ModbusFaults, ExceptionResponseFaultsTheAxisAndResetRecovers) {
  Loopback lb("cia402.yaml");
  ASSERT_TRUE(lb.enable());
  lb.server->fail_next(1, modbus::ModbusError::server_device_busy);
  lb.cycle();
  EXPECT_TRUE(is_link_fault(lb.fb(), modbus::ModbusError::server_device_busy)) << lb.fb().fault.describe();
  EXPECT_STREQ(lb.fb().fault.code.category().name(), "modbus");
  EXPECT_EQ(lb.fb().fault.code.value(), 6);
  // Latched: later good exchanges do not clear it by themselves.
  for (int i = 0; i < 5; ++i) lb.cycle();
  EXPECT_EQ(lb.fb().state, DriveState::fault);
  lb.drive->request(DriveRequest::fault_reset);
  lb.cycle();
  EXPECT_FALSE(lb.fb().fault);
  EXPECT_EQ(lb.drive->link_stats().connects, 1u);  // an exception keeps the connection
  ASSERT_TRUE(lb.enable());
}

TEST(ModbusFaults, EveryExceptionCodeMapsToItsValue) {
  Loopback lb("vendor_simple.yaml");
  lb.cycle();
  for (int code : {1, 2, 3, 4, 5, 6, 7, 8, 10, 11}) {
    SCOPED_TRACE(code);
    lb.server->fail_next(1, static_cast<modbus::ModbusError>(code));
    lb.cycle();
    EXPECT_EQ(lb.fb().state, DriveState::fault);
    EXPECT_EQ(lb.fb().fault.code.value(), code);
    EXPECT_FALSE(lb.fb().fault.text.empty());
    lb.drive->request(DriveRequest::fault_reset);
    lb.cycle();
    EXPECT_FALSE(lb.fb().fault) << lb.fb().fault.describe();
  }
}

TEST(ModbusFaults, SlowResponsePastTimeoutFaultsThenRecovers) {
  Loopback lb("cia402.yaml", milliseconds(30));
  ASSERT_TRUE(lb.enable());
  lb.server->set_response_delay(milliseconds(120));
  lb.cycle();
  EXPECT_TRUE(is_link_fault(lb.fb(), modbus::ModbusError::timeout)) << lb.fb().fault.describe();
  EXPECT_FALSE(lb.drive->link_stats().connected);  // dropped: a late reply must not pass for the next one
  lb.server->set_response_delay(Duration{});
  // Reconnects after the back-off (virtual time), but stays faulted until reset.
  ASSERT_TRUE(lb.cycle_until(
      [&] {
        return lb.drive->link_stats().connected && lb.drive->link_stats().exchanges > 0 && lb.fb().age == Duration{};
      },
      200));
  EXPECT_EQ(lb.fb().state, DriveState::fault);
  lb.drive->request(DriveRequest::fault_reset);
  lb.cycle();
  EXPECT_FALSE(lb.fb().fault);
  ASSERT_TRUE(lb.enable());
  EXPECT_GE(lb.drive->link_stats().connects, 2u);
}

TEST(ModbusFaults, ServerKilledAndRestartedMidRun) {
  Loopback lb("cia402.yaml");
  ASSERT_TRUE(lb.enable());
  for (int i = 1; i <= 100; ++i) {
    lb.command.position_inc = i * 50;
    lb.cycle();
  }
  const auto pos_before = lb.fb().position_inc;
  const std::uint16_t port = lb.server->port();
  lb.server->stop();
  lb.cycle();
  EXPECT_EQ(lb.fb().state, DriveState::fault);
  EXPECT_TRUE(is_link_fault(lb.fb(), modbus::ModbusError::connection_lost)) << lb.fb().fault.describe();
  // While it is down: connect attempts with back-off fail, the image ages, the fault stays.
  for (int i = 0; i < 100; ++i) lb.cycle();
  EXPECT_EQ(lb.fb().state, DriveState::fault);
  EXPECT_EQ(lb.fb().fault.code, modbus::make_error_code(modbus::ModbusError::connect_failed));
  EXPECT_GE(lb.fb().age, milliseconds(100));
  EXPECT_EQ(lb.fb().position_inc, pos_before);
  const auto errors_down = lb.drive->link_stats().errors;
  EXPECT_GE(errors_down, 2u);
  EXPECT_LT(errors_down, 10u);  // back-off: not one attempt per cycle
  // A reset while the link is down does not clear the fault.
  lb.drive->request(DriveRequest::fault_reset);
  lb.cycle();
  EXPECT_EQ(lb.fb().state, DriveState::fault);
  // The drive comes back (power-cycled: fresh state) on the same port.
  lb.server->with_device([&](mocks::DriveDevice& d) { d = mocks::DriveDevice(lb.profile); });
  ASSERT_FALSE(lb.server->start());
  EXPECT_EQ(lb.server->port(), port);
  ASSERT_TRUE(lb.cycle_until([&] { return lb.fb().age == Duration{}; }, 1000));
  EXPECT_EQ(lb.fb().state, DriveState::fault);  // still latched until reset
  lb.drive->request(DriveRequest::fault_reset);
  ASSERT_TRUE(lb.cycle_until([&] { return lb.fb().state == DriveState::switch_on_disabled; }, 5));
  lb.command.position_inc = lb.fb().position_inc;
  ASSERT_TRUE(lb.enable());
}

TEST(ModbusFaults, MalformedClientsDoNotDisturbOthers) {
  Loopback lb("cia402.yaml");
  ASSERT_TRUE(lb.enable());
  const std::uint16_t port = lb.server->port();
  // 1. Bad protocol id: logged, that connection closed.
  RawSocket garbage(port);
  ASSERT_TRUE(garbage.connected());
  ASSERT_TRUE(garbage.send({0x00, 0x01, 0x12, 0x34, 0x00, 0x06, 0x01, 0x03, 0x00, 0x0A, 0x00, 0x01}));
  EXPECT_TRUE(garbage.peer_closed());
  // 2. MBAP length 0xFFFF.
  RawSocket too_long(port);
  ASSERT_TRUE(too_long.send({0x00, 0x01, 0x00, 0x00, 0xFF, 0xFF, 0x01, 0x03}));
  EXPECT_TRUE(too_long.peer_closed());
  // 3. Half a frame, then the client vanishes.
  {
    RawSocket half(port);
    ASSERT_TRUE(half.send({0x00, 0x07, 0x00, 0x00, 0x00, 0x06, 0x01, 0x03}));
  }
  // 4. A frame whose MBAP length disagrees with the PDU (FC 3 with two extra bytes): exception
  //    03, and the same connection keeps working because framing follows the MBAP length.
  RawSocket wrong_len(port);
  ASSERT_TRUE(wrong_len.send({0x00, 0x09, 0x00, 0x00, 0x00, 0x08, 0x01, 0x03, 0x00, 0x0A, 0x00, 0x01, 0xAA, 0xBB}));
  EXPECT_EQ(wrong_len.recv(9), (std::vector<std::uint8_t>{0x00, 0x09, 0x00, 0x00, 0x00, 0x03, 0x01, 0x83, 0x03}));
  ASSERT_TRUE(wrong_len.send({0x00, 0x0A, 0x00, 0x00, 0x00, 0x06, 0x01, 0x03, 0x00, 0x0A, 0x00, 0x01}));
  const auto ok = wrong_len.recv(11);
  ASSERT_EQ(ok.size(), 11u);
  EXPECT_EQ(ok[7], 0x03);
  EXPECT_EQ(ok[8], 0x02);
  // 5. Unknown function code with trailing bytes (desynchronises libmodbus 3.1.6 servers).
  ASSERT_TRUE(wrong_len.send({0x00, 0x0B, 0x00, 0x00, 0x00, 0x05, 0x01, 0x42, 0x01, 0x02, 0x03, 0x00,
                              0x0C, 0x00, 0x00, 0x00, 0x06, 0x01, 0x03, 0x00, 0x0A, 0x00, 0x01}));
  EXPECT_EQ(wrong_len.recv(9), (std::vector<std::uint8_t>{0x00, 0x0B, 0x00, 0x00, 0x00, 0x03, 0x01, 0xC2, 0x01}));
  const auto next = wrong_len.recv(11);
  ASSERT_EQ(next.size(), 11u);
  EXPECT_EQ(next[1], 0x0C);
  // Meanwhile the axis never noticed.
  for (int i = 0; i < 50; ++i) lb.cycle();
  EXPECT_EQ(lb.fb().state, DriveState::operation_enabled);
  EXPECT_EQ(lb.drive->link_stats().errors, 0u);
  EXPECT_EQ(lb.server->stats().malformed, 2u);
}

TEST(ModbusFaults, StalledPartialFrameIsClosedAndSlotsAreLimited) {
  mocks::ModbusServerConfig config;
  config.frame_timeout = milliseconds(300);
  config.max_connections = 2;
  mocks::ModbusDriveServer server(mocks::DriveDevice(shipped_profile("cia402.yaml")), config);
  ASSERT_FALSE(server.start());
  RawSocket stalled(server.port());
  ASSERT_TRUE(stalled.send({0x00, 0x07, 0x00, 0x00, 0x00, 0x06, 0x01, 0x03}));  // 8 of 12 bytes
  RawSocket second(server.port());
  RawSocket third(server.port());  // over max_connections: accepted and closed at once
  EXPECT_TRUE(third.peer_closed());
  EXPECT_TRUE(stalled.peer_closed());  // after frame_timeout (real time, bounded by the 2 s receive timeout)
  EXPECT_EQ(server.stats().stalled, 1u);
  ASSERT_TRUE(second.send({0x00, 0x08, 0x00, 0x00, 0x00, 0x06, 0x01, 0x03, 0x00, 0x0A, 0x00, 0x01}));
  EXPECT_EQ(second.recv(11).size(), 11u);  // the healthy client is still served
}

TEST(ModbusFaults, SeveralClientsAtOnceWhileTheAxisRuns) {
  Loopback lb("cia402.yaml");
  ASSERT_TRUE(lb.enable());
  const std::uint16_t port = lb.server->port();
  std::atomic<int> failures{0}, reads{0};
  std::vector<std::thread> clients;
  for (int c = 0; c < 8; ++c) {
    clients.emplace_back([&, c] {
      modbus_t* ctx = modbus_new_tcp("127.0.0.1", port);
      if (!ctx || modbus_connect(ctx) != 0) {
        failures += 100;
        if (ctx) modbus_free(ctx);
        return;
      }
      std::uint16_t regs[6];
      for (int i = 0; i < 200; ++i) {
        if (modbus_read_registers(ctx, 10, 6, regs) != 6 || (regs[0] & 0x6F) != 0x27)
          ++failures;
        else
          ++reads;
        if (c == 0 && modbus_write_register(ctx, 10, 0) != -1) ++failures;  // read-only
      }
      modbus_close(ctx);
      modbus_free(ctx);
    });
  }
  for (int i = 0; i < 100; ++i) lb.cycle();
  for (auto& t : clients) t.join();
  EXPECT_EQ(failures.load(), 0);
  EXPECT_EQ(reads.load(), 8 * 200);
  EXPECT_EQ(lb.fb().state, DriveState::operation_enabled);
  EXPECT_EQ(lb.drive->link_stats().errors, 0u);
  EXPECT_GE(lb.server->stats().connections_accepted, 9u);
}

TEST(ModbusFaults, ReadOnlyWriteThroughLibmodbusIsIllegalDataAddress) {
  Loopback lb("cia402.yaml");
  modbus_t* ctx = modbus_new_tcp("127.0.0.1", lb.server->port());
  ASSERT_NE(ctx, nullptr);
  ASSERT_EQ(modbus_connect(ctx), 0);
  EXPECT_EQ(modbus_write_register(ctx, 10, 0x1234), -1);  // status word
  EXPECT_EQ(errno, EMBXILADD);
  const std::uint16_t two[2] = {1, 2};
  EXPECT_EQ(modbus_write_registers(ctx, 5, 2, two), -1);  // spans target velocity (rw) and a gap
  EXPECT_EQ(errno, EMBXILADD);
  std::uint16_t r[4];
  EXPECT_EQ(modbus_read_registers(ctx, 6, 4, r), -1);  // gap between command and feedback blocks
  EXPECT_EQ(errno, EMBXILADD);
  EXPECT_EQ(modbus_read_input_registers(ctx, 0, 1, r), -1);  // cia402 profile has no input registers
  EXPECT_EQ(errno, EMBXILADD);
  std::uint8_t bits[8];
  EXPECT_EQ(modbus_read_bits(ctx, 0, 8, bits), -1);
  EXPECT_EQ(errno, EMBXILFUN);
  modbus_close(ctx);
  modbus_free(ctx);
}

TEST(ModbusServer, ListensOnAHostNameAndNamesABadOne) {
  mocks::ModbusServerConfig config;
  config.listen_host = "localhost";
  mocks::ModbusDriveServer server(mocks::DriveDevice(shipped_profile("cia402.yaml")), config);
  ASSERT_FALSE(server.start());
  modbus_t* ctx = modbus_new_tcp("127.0.0.1", server.port());
  ASSERT_NE(ctx, nullptr);
  EXPECT_EQ(modbus_connect(ctx), 0) << "localhost resolves to the loopback address";
  std::uint16_t sw = 0;
  EXPECT_EQ(modbus_read_registers(ctx, 10, 1, &sw), 1);
  modbus_close(ctx);
  modbus_free(ctx);
  server.stop();

  config.listen_host = "no-such-host.invalid";
  mocks::ModbusDriveServer bad(mocks::DriveDevice(shipped_profile("cia402.yaml")), config);
  EXPECT_TRUE(bad.start()) << "an unknown host is an error, not a crash";
}

TEST(ModbusFaults, ConnectRefusedBacksOffAndConnectsLater) {
  Loopback lb("vendor_simple.yaml");
  const std::uint16_t port = lb.server->port();
  lb.server->stop();
  lb.make_drive(milliseconds(50));  // a fresh drive that never saw the server
  for (int i = 0; i < 20; ++i) lb.cycle();
  EXPECT_EQ(lb.fb().state, DriveState::fault);
  EXPECT_EQ(lb.fb().fault.code, modbus::make_error_code(modbus::ModbusError::connect_failed));
  ASSERT_FALSE(lb.server->start());
  ASSERT_EQ(lb.server->port(), port);
  ASSERT_TRUE(lb.cycle_until([&] { return lb.drive->link_stats().connected; }, 1000));
  lb.drive->request(DriveRequest::fault_reset);
  lb.cycle();
  lb.cycle();
  EXPECT_EQ(lb.fb().state, DriveState::switch_on_disabled);
}

}  // namespace
}  // namespace hil::test
