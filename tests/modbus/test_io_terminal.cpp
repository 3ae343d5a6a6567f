// SPDX-License-Identifier: MIT
// The simulated I/O terminal: coils and discrete inputs (FC 1, 2, 5, 15) through our request
// checks and libmodbus' modbus_reply(), table-driven; then a libmodbus client against the
// terminal served over loopback TCP.
#include <gtest/gtest.h>
#include <modbus.h>

#include <memory>
#include <vector>

#include "hil/mocks/modbus_io_terminal.hpp"
#include "hil/mocks/modbus_server.hpp"
#include "hil/modbus/adu.hpp"

namespace hil::mocks {
namespace {

using Bytes = std::vector<std::uint8_t>;

class Terminal : public ::testing::Test {
 protected:
  Bytes run(Bytes pdu) {
    Bytes adu(7);
    modbus::make_mbap(adu.data(), 0x0102, 1, pdu.size());
    adu.insert(adu.end(), pdu.begin(), pdu.end());
    Bytes out(modbus::kMaxAduSize);
    last = terminal.handle(adu, out, {});
    out.resize(last.size);
    if (out.size() >= 7) out.erase(out.begin(), out.begin() + 7);
    return out;
  }
  IoTerminal terminal{IoTerminalConfig{.coils = 20, .discrete_inputs = 12}};
  modbus::HandleResult last;
};

TEST_F(Terminal, ReadsCoilsAndDiscreteInputsLsbFirst) {
  terminal.set_coil(0, true);
  terminal.set_coil(3, true);
  terminal.set_coil(9, true);
  // MB spec §6.1: the first coil is the LSB of the first byte; unused high bits are 0.
  EXPECT_EQ(run({0x01, 0x00, 0x00, 0x00, 0x0A}), (Bytes{0x01, 0x02, 0x09, 0x02}));
  terminal.set_discrete_input(11, true);
  EXPECT_EQ(run({0x02, 0x00, 0x04, 0x00, 0x08}), (Bytes{0x02, 0x01, 0x80}));
  EXPECT_EQ(last.coils_written_count, 0);
}

TEST_F(Terminal, WritesCoilsAndReportsThem) {
  EXPECT_EQ(run({0x05, 0x00, 0x07, 0xFF, 0x00}), (Bytes{0x05, 0x00, 0x07, 0xFF, 0x00}));
  EXPECT_TRUE(terminal.coil(7));
  EXPECT_EQ(last.coils_written_first, 7);
  EXPECT_EQ(last.coils_written_count, 1);
  EXPECT_EQ(last.written_count, 0);  // no holding register was written
  EXPECT_EQ(run({0x05, 0x00, 0x07, 0x00, 0x00}), (Bytes{0x05, 0x00, 0x07, 0x00, 0x00}));
  EXPECT_FALSE(terminal.coil(7));
  // FC 15: 10 coils from 4, values 0xCD 0x01 (MB spec §6.11 example: 1011 0011 ...).
  EXPECT_EQ(run({0x0F, 0x00, 0x04, 0x00, 0x0A, 0x02, 0xCD, 0x01}), (Bytes{0x0F, 0x00, 0x04, 0x00, 0x0A}));
  const bool want[10] = {true, false, true, true, false, false, true, true, true, false};
  for (std::uint16_t i = 0; i < 10; ++i) EXPECT_EQ(terminal.coil(static_cast<std::uint16_t>(4 + i)), want[i]) << i;
  EXPECT_EQ(terminal.coil_write_requests(), 3u);
  EXPECT_EQ(terminal.coils_written(), 12u);
}

struct ExceptionCase {
  const char* what;
  Bytes pdu;
  std::uint8_t code;
};

TEST_F(Terminal, ExceptionsTableDriven) {
  const std::vector<ExceptionCase> cases = {
      {"FC1 quantity 0", {0x01, 0x00, 0x00, 0x00, 0x00}, 3},
      {"FC1 quantity 2001 (03 before 02)", {0x01, 0xFF, 0x00, 0x07, 0xD1}, 3},
      {"FC1 past the last coil", {0x01, 0x00, 0x10, 0x00, 0x05}, 2},
      {"FC1 trailing byte", {0x01, 0x00, 0x00, 0x00, 0x01, 0x00}, 3},
      {"FC2 past the last input", {0x02, 0x00, 0x0B, 0x00, 0x02}, 2},
      {"FC2 truncated", {0x02, 0x00}, 3},
      {"FC5 value neither 0000 nor FF00", {0x05, 0x00, 0x01, 0x00, 0x01}, 3},
      {"FC5 absent coil", {0x05, 0x00, 0x14, 0xFF, 0x00}, 2},
      {"FC15 byte count mismatch", {0x0F, 0x00, 0x00, 0x00, 0x09, 0x01, 0xFF}, 3},
      {"FC15 length mismatch", {0x0F, 0x00, 0x00, 0x00, 0x08, 0x01, 0xFF, 0x00}, 3},
      {"FC15 quantity 1969", {0x0F, 0x00, 0x00, 0x07, 0xB1, 0xF7}, 3},
      {"FC15 past the last coil", {0x0F, 0x00, 0x10, 0x00, 0x08, 0x01, 0xFF}, 2},
      {"FC3: the terminal has no registers", {0x03, 0x00, 0x00, 0x00, 0x01}, 2},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.what);
    const Bytes rsp = run(c.pdu);
    ASSERT_EQ(rsp.size(), 2u);
    EXPECT_EQ(rsp[0], c.pdu[0] | 0x80);
    EXPECT_EQ(rsp[1], c.code);
    EXPECT_EQ(last.coils_written_count, 0);
  }
  EXPECT_EQ(terminal.coil_write_requests(), 0u);
}

TEST(TerminalWithoutInputs, AnswersIllegalFunctionForTheMissingTable) {
  IoTerminal t{IoTerminalConfig{.coils = 4, .discrete_inputs = 0}};
  Bytes adu(7);
  const Bytes pdu = {0x02, 0x00, 0x00, 0x00, 0x01};
  modbus::make_mbap(adu.data(), 1, 1, pdu.size());
  adu.insert(adu.end(), pdu.begin(), pdu.end());
  Bytes out(modbus::kMaxAduSize);
  const auto r = t.handle(adu, out, {});
  ASSERT_EQ(r.size, 9u);
  EXPECT_EQ(out[7], 0x82);
  EXPECT_EQ(out[8], 0x01);
}

struct CtxDeleter {
  void operator()(modbus_t* c) const noexcept {
    modbus_close(c);
    modbus_free(c);
  }
};

TEST(TerminalOverTcp, LibmodbusClientReadsAndWritesBits) {
  ModbusDriveServer server(IoTerminal{IoTerminalConfig{.coils = 32, .discrete_inputs = 16}}, ModbusServerConfig{});
  ASSERT_FALSE(server.start());
  std::unique_ptr<modbus_t, CtxDeleter> ctx(modbus_new_tcp("127.0.0.1", server.port()));
  ASSERT_TRUE(ctx);
  modbus_set_response_timeout(ctx.get(), 2, 0);
  modbus_set_slave(ctx.get(), 1);
  ASSERT_EQ(modbus_connect(ctx.get()), 0);

  ASSERT_EQ(modbus_write_bit(ctx.get(), 5, 1), 1);  // FC 5
  const std::uint8_t values[4] = {1, 0, 1, 1};
  ASSERT_EQ(modbus_write_bits(ctx.get(), 20, 4, values), 4);  // FC 15
  std::uint8_t got[32] = {};
  ASSERT_EQ(modbus_read_bits(ctx.get(), 0, 32, got), 32);  // FC 1
  for (int i = 0; i < 32; ++i) {
    const bool want = i == 5 || i == 20 || i == 22 || i == 23;
    EXPECT_EQ(got[i] != 0, want) << i;
  }
  server.with_terminal([](IoTerminal& t) {
    EXPECT_TRUE(t.coil(22));
    t.set_discrete_input(3, true);
    t.set_discrete_input(15, true);
  });
  std::uint8_t in[16] = {};
  ASSERT_EQ(modbus_read_input_bits(ctx.get(), 0, 16, in), 16);  // FC 2
  for (int i = 0; i < 16; ++i) EXPECT_EQ(in[i] != 0, i == 3 || i == 15) << i;

  // Exceptions arrive as libmodbus errors with the exception code.
  EXPECT_EQ(modbus_read_input_bits(ctx.get(), 10, 8, in), -1);
  EXPECT_EQ(errno, EMBXILADD);
  EXPECT_EQ(modbus_write_bit(ctx.get(), 32, 1), -1);
  EXPECT_EQ(errno, EMBXILADD);
  EXPECT_EQ(server.with_terminal([](IoTerminal& t) { return t.coil_write_requests(); }), 2u);
  EXPECT_THROW(server.with_device([](DriveDevice&) {}), std::bad_variant_access);
}

}  // namespace
}  // namespace hil::mocks
