// SPDX-License-Identifier: MIT
// Pure Modbus pieces: framing, packing, the request handler (table-driven), error mapping.
#include <gtest/gtest.h>

#include <cerrno>
#include <vector>

#include "hil/mocks/modbus_responder.hpp"
#include "hil/modbus/adu.hpp"
#include "hil/modbus/error.hpp"
#include "hil/modbus/packing.hpp"
#include "hil/modbus/request_handler.hpp"

namespace hil::modbus {
namespace {

using Bytes = std::vector<std::uint8_t>;

TEST(ModbusFrame, CompleteNeedMoreAndBadHeaders) {
  const Bytes req = {0x00, 0x01, 0x00, 0x00, 0x00, 0x06, 0x01, 0x03, 0x00, 0x00, 0x00, 0x02};
  auto c = check_frame(req);
  EXPECT_EQ(c.status, FrameStatus::complete);
  EXPECT_EQ(c.size, 12u);
  EXPECT_EQ(c.header.transaction_id, 1);
  EXPECT_EQ(check_frame(std::span(req).first(6)).status, FrameStatus::need_more);
  EXPECT_EQ(check_frame(std::span(req).first(11)).status, FrameStatus::need_more);
  Bytes bad_pid = req;
  bad_pid[3] = 1;  // libmodbus 3.1.6 misses a protocol id with one zero byte; we do not
  EXPECT_EQ(check_frame(bad_pid).status, FrameStatus::bad_protocol_id);
  Bytes short_len = req;
  short_len[5] = 1;
  EXPECT_EQ(check_frame(short_len).status, FrameStatus::bad_length);
  Bytes long_len = req;
  long_len[4] = 0x01;  // 262 > 254
  EXPECT_EQ(check_frame(long_len).status, FrameStatus::bad_length);
}

TEST(ModbusPacking, WordOrderSignednessSaturation) {
  std::uint16_t r[2] = {};
  pack_value(0x12345678, {2, false, WordOrder::high_first}, r);
  EXPECT_EQ(r[0], 0x1234);
  EXPECT_EQ(r[1], 0x5678);
  pack_value(0x12345678, {2, false, WordOrder::low_first}, r);
  EXPECT_EQ(r[0], 0x5678);
  EXPECT_EQ(r[1], 0x1234);
  pack_value(-2, {2, true, WordOrder::low_first}, r);
  EXPECT_EQ(unpack_value(r, {2, true, WordOrder::low_first}), -2);
  EXPECT_EQ(unpack_value(r, {2, false, WordOrder::low_first}), 0xFFFFFFFE);
  pack_value(-5, {1, true}, r);
  EXPECT_EQ(r[0], 0xFFFB);
  EXPECT_EQ(unpack_value(r, {1, true}), -5);
  pack_value(std::int64_t{1} << 40, {2, true}, r);  // saturates instead of wrapping
  EXPECT_EQ(unpack_value(r, {2, true}), INT32_MAX);
  pack_value(-70000, {1, true}, r);
  EXPECT_EQ(unpack_value(r, {1, true}), INT16_MIN);
  pack_value(-1, {1, false}, r);
  EXPECT_EQ(r[0], 0);
}

TEST(ModbusError, CategoryAndLibmodbusErrno) {
  std::error_code ec = ModbusError::illegal_data_address;
  EXPECT_STREQ(ec.category().name(), "modbus");
  EXPECT_EQ(ec.value(), 2);
  EXPECT_NE(ec.message().find("illegal data address"), std::string::npos);
  EXPECT_EQ(from_libmodbus_errno(112345678 + 6), ModbusError::server_device_busy);
  EXPECT_EQ(from_libmodbus_errno(112345678 + 11), ModbusError::gateway_target_failed);
  EXPECT_EQ(from_libmodbus_errno(112345678 + 13), ModbusError::invalid_response);  // EMBBADDATA
  EXPECT_EQ(from_libmodbus_errno(ETIMEDOUT), ModbusError::timeout);
  EXPECT_EQ(from_libmodbus_errno(ECONNREFUSED), ModbusError::connect_failed);
  EXPECT_EQ(from_libmodbus_errno(ECONNRESET), ModbusError::connection_lost);
  EXPECT_FALSE(exception_from_code(9));
  EXPECT_FALSE(exception_from_code(0));
  for (int c : {1, 2, 3, 4, 5, 6, 7, 8, 10, 11}) EXPECT_TRUE(exception_from_code(static_cast<std::uint8_t>(c)));
}

class ModbusHandler : public ::testing::Test {
 protected:
  void SetUp() override {
    table.define(RegisterSpace::holding, 0, 6, Access::read_write);
    table.define(RegisterSpace::holding, 10, 7, Access::read_only);
    table.define(RegisterSpace::input, 0, 5, Access::read_only);
    for (std::uint16_t a = 0; a < 20; ++a) table.set(RegisterSpace::holding, a, static_cast<std::uint16_t>(0x100 + a));
    table.set(RegisterSpace::input, 2, 0xBEEF);
  }
  Bytes run(Bytes pdu, std::uint8_t unit = 1) {
    Bytes adu(7);
    make_mbap(adu.data(), 0x4242, unit, pdu.size());
    adu.insert(adu.end(), pdu.begin(), pdu.end());
    Bytes out(kMaxAduSize);
    last = responder.handle(adu, table, out, options);
    out.resize(last.size);
    if (out.size() >= 7) {
      EXPECT_EQ(out[0], 0x42);
      EXPECT_EQ(out[1], 0x42);
      EXPECT_EQ(get_u16(out.data() + 4), out.size() - 6);
      EXPECT_EQ(out[6], unit);
      out.erase(out.begin(), out.begin() + 7);
    }
    return out;  // response PDU
  }
  RegisterTable table;
  hil::mocks::ModbusResponder responder;  // libmodbus' modbus_reply() behind our request checks
  HandlerOptions options;
  HandleResult last;
};

TEST_F(ModbusHandler, Fc3Fc4Reads) {
  EXPECT_EQ(run({0x03, 0x00, 0x0A, 0x00, 0x02}), (Bytes{0x03, 0x04, 0x01, 0x0A, 0x01, 0x0B}));
  EXPECT_EQ(run({0x04, 0x00, 0x02, 0x00, 0x01}), (Bytes{0x04, 0x02, 0xBE, 0xEF}));
}

struct ExceptionCase {
  const char* what;
  Bytes pdu;
  std::uint8_t code;
};

TEST_F(ModbusHandler, ExceptionsTableDriven) {
  const std::vector<ExceptionCase> cases = {
      {"unknown function", {0x2B, 0x0E, 0x01, 0x00}, 1},
      {"coils not served", {0x01, 0x00, 0x00, 0x00, 0x01}, 1},
      {"read gap register", {0x03, 0x00, 0x05, 0x00, 0x06}, 2},
      {"read past end", {0x03, 0x00, 0x10, 0x00, 0x02}, 2},
      {"read quantity 0", {0x03, 0x00, 0x00, 0x00, 0x00}, 3},
      {"read quantity 126 (03 before 02)", {0x03, 0xFF, 0x00, 0x00, 0x7E}, 3},
      {"read with trailing byte", {0x03, 0x00, 0x00, 0x00, 0x01, 0x00}, 3},
      {"read truncated", {0x03, 0x00}, 3},
      {"input register absent", {0x04, 0x00, 0x05, 0x00, 0x01}, 2},
      {"FC6 to read-only register", {0x06, 0x00, 0x0A, 0x12, 0x34}, 2},
      {"FC16 over read-only", {0x10, 0x00, 0x04, 0x00, 0x03, 0x06, 0, 1, 0, 2, 0, 3}, 2},
      {"FC16 byte count mismatch", {0x10, 0x00, 0x00, 0x00, 0x02, 0x03, 0, 1, 0}, 3},
      {"FC16 length mismatch", {0x10, 0x00, 0x00, 0x00, 0x01, 0x02, 0, 1, 0xFF}, 3},
      {"FC16 quantity 124", {0x10, 0x00, 0x00, 0x00, 0x7C, 0xF8}, 3},
      {"FC22 read-only", {0x16, 0x00, 0x0A, 0xFF, 0xFF, 0x00, 0x00}, 2},
      {"FC23 write to read-only", {0x17, 0x00, 0x0A, 0x00, 0x01, 0x00, 0x0A, 0x00, 0x01, 0x02, 0x00, 0x01}, 2},
      {"FC23 read quantity 0", {0x17, 0x00, 0x0A, 0x00, 0x00, 0x00, 0x00, 0x00, 0x01, 0x02, 0x00, 0x01}, 3},
      {"exception FC in request", {0x83, 0x00}, 1},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.what);
    const Bytes rsp = run(c.pdu);
    ASSERT_EQ(rsp.size(), 2u);
    EXPECT_EQ(rsp[0], c.pdu[0] | 0x80);
    EXPECT_EQ(rsp[1], c.code);
    EXPECT_EQ(static_cast<int>(last.error), c.code);
    EXPECT_EQ(last.written_count, 0);
  }
}

TEST_F(ModbusHandler, WritesEchoAndReport) {
  EXPECT_EQ(run({0x06, 0x00, 0x00, 0x00, 0x0F}), (Bytes{0x06, 0x00, 0x00, 0x00, 0x0F}));
  EXPECT_EQ(table.get(RegisterSpace::holding, 0), 0x000F);
  EXPECT_EQ(last.written_first, 0);
  EXPECT_EQ(last.written_count, 1);
  EXPECT_EQ(run({0x10, 0x00, 0x02, 0x00, 0x02, 0x04, 0xDE, 0xAD, 0xBE, 0xEF}), (Bytes{0x10, 0x00, 0x02, 0x00, 0x02}));
  EXPECT_EQ(table.get(RegisterSpace::holding, 2), 0xDEAD);
  EXPECT_EQ(table.get(RegisterSpace::holding, 3), 0xBEEF);
  table.set(RegisterSpace::holding, 1, 0x0012);
  EXPECT_EQ(run({0x16, 0x00, 0x01, 0x00, 0xF2, 0x00, 0x25}), (Bytes{0x16, 0x00, 0x01, 0x00, 0xF2, 0x00, 0x25}));
  EXPECT_EQ(table.get(RegisterSpace::holding, 1), 0x0017);  // MB spec §6.16 example
}

TEST_F(ModbusHandler, Fc23WritesBeforeReading) {
  const Bytes rsp = run({0x17, 0x00, 0x00, 0x00, 0x02, 0x00, 0x00, 0x00, 0x01, 0x02, 0xAB, 0xCD});
  EXPECT_EQ(rsp, (Bytes{0x17, 0x04, 0xAB, 0xCD, 0x01, 0x01}));
  EXPECT_EQ(last.written_first, 0);
  EXPECT_EQ(last.written_count, 1);
}

TEST_F(ModbusHandler, UnitPolicy) {
  EXPECT_EQ(run({0x03, 0x00, 0x0A, 0x00, 0x01}, 17).size(), 4u);  // lenient: like libmodbus TCP
  options.strict_unit = true;
  EXPECT_EQ(run({0x03, 0x00, 0x0A, 0x00, 0x01}, 17), (Bytes{0x83, 0x0B}));
  EXPECT_EQ(run({0x03, 0x00, 0x0A, 0x00, 0x01}, 0xFF).size(), 4u);
  EXPECT_EQ(run({0x03, 0x00, 0x0A, 0x00, 0x01}, 1).size(), 4u);
}

TEST_F(ModbusHandler, MalformedAduGetsNoResponse) {
  Bytes out(kMaxAduSize);
  const Bytes bad = {0x00, 0x01, 0x00, 0x00, 0x00, 0x06, 0x01, 0x03, 0x00};  // shorter than its length
  auto r = responder.handle(bad, table, out, options);
  EXPECT_EQ(r.size, 0u);
  EXPECT_EQ(r.error, ModbusError::invalid_request);
  const Bytes pid = {0x00, 0x01, 0x00, 0x01, 0x00, 0x02, 0x01, 0x03};
  EXPECT_EQ(responder.handle(pid, table, out, options).size, 0u);
}

}  // namespace
}  // namespace hil::modbus
