// SPDX-License-Identifier: MIT
// Serial byte stream: line formats, software parity, PARMRK error marks, XON/XOFF with
// configurable (parity-carrying) bytes, stall timeout on the virtual clock, a real pty pair.
#include <gtest/gtest.h>

#include <deque>
#include <thread>

#include "hil/serial/line_format.hpp"
#include "hil/serial/linux/ports.hpp"
#include "hil/serial/memory_line.hpp"
#include "hil/serial/serial_stream.hpp"

using namespace hil::serial;
using namespace std::chrono_literals;

namespace {
std::span<const std::uint8_t> bytes(const std::string& s) {
  return {reinterpret_cast<const std::uint8_t*>(s.data()), s.size()};
}
std::string read_all(ByteStream& s, std::size_t n, hil::Duration timeout = 100ms) {
  std::string out;
  std::array<std::uint8_t, 64> buf{};
  while (out.size() < n) {
    auto r = s.read_some(buf, timeout);
    out.append(reinterpret_cast<const char*>(buf.data()), r.size);
    if (r.error) break;
  }
  return out;
}
}  // namespace

TEST(LineFormat, ParsesShorthandAndComputesLineTime) {
  auto f = parse_char_format("7E2");
  ASSERT_TRUE(f);
  EXPECT_EQ(f->data_bits, 7);
  EXPECT_EQ(f->parity, Parity::even);
  EXPECT_EQ(f->stop_bits, StopBits::two);
  EXPECT_EQ(f->half_bits_per_char(), 22U);  // 1 + 7 + 1 + 2 = 11 bits
  f->baud = 9600;
  EXPECT_EQ(f->line_time(9600).count(), 11'000'000'000LL);  // 9600 chars of 11 bits at 9600 Bd
  auto h = parse_char_format("8N1.5");
  ASSERT_TRUE(h);
  EXPECT_EQ(h->half_bits_per_char(), 2U * 9U + 3U);
  EXPECT_FALSE(parse_char_format("9N1"));
  EXPECT_FALSE(parse_char_format("8X1"));
  EXPECT_FALSE(parse_char_format("8N3"));
  LineFormat slow;
  slow.baud = 110;
  EXPECT_TRUE(validate(slow));
  slow.baud = 109;
  EXPECT_FALSE(validate(slow));
  slow.baud = 115201;
  EXPECT_FALSE(validate(slow));
  LineFormat odd;
  odd.baud = 250;  // non-standard rates are allowed
  EXPECT_TRUE(validate(odd));
  EXPECT_EQ(parse_char_format("7E2")->describe(), "9600 7E2");
}

TEST(LineFormat, SoftwareParityBits) {
  EXPECT_EQ(with_parity7(0x11, Parity::even), 0x11);  // DC1: two ones
  EXPECT_EQ(with_parity7(0x13, Parity::even), 0x93);  // DC3: three ones -> parity bit set
  EXPECT_EQ(with_parity7(0x13, Parity::odd), 0x13);
  EXPECT_TRUE(parity7_ok(0x93, Parity::even));
  EXPECT_FALSE(parity7_ok(0x13, Parity::even));
}

TEST(SerialStream, SoftwareParityRoundTripAndErrorReported) {
  hil::VirtualClock clock;
  auto line = make_memory_line(&clock);
  LineFormat f = *parse_char_format("7E1");
  Discipline d{.software_parity = true};
  SerialStream a(std::move(line.a), f, d, clock);
  SerialStream b(std::move(line.b), f, d, clock);
  ASSERT_FALSE(a.write(bytes("#3N0001 NOP\r\n"), 1s));
  EXPECT_EQ(read_all(b, 13), "#3N0001 NOP\r\n");
  // Flip one bit in flight: the receiver reports a parity error at that character.
  *line.a_to_b = [](std::vector<std::uint8_t>& v) { v[2] ^= 0x80; };
  ASSERT_FALSE(a.write(bytes("ABCD"), 1s));
  std::array<std::uint8_t, 16> buf{};
  auto r = b.read_some(buf, 100ms);
  EXPECT_EQ(r.size, 2U);
  EXPECT_EQ(r.error, LineError::parity);
  r = b.read_some(buf, 100ms);
  EXPECT_EQ(std::string(reinterpret_cast<char*>(buf.data()), r.size), "D");
}

namespace {
/// Raw line fed from a script (for PARMRK marks as a tty delivers them).
class ScriptedLine final : public RawLine {
 public:
  std::deque<std::vector<std::uint8_t>> chunks;
  std::uint64_t overruns = 0;
  ReadResult read_some(std::span<std::uint8_t> buf, hil::Duration) override {
    if (chunks.empty()) return {0, LineError::timeout};
    auto c = chunks.front();
    chunks.pop_front();
    std::copy(c.begin(), c.end(), buf.begin());
    return {c.size(), {}};
  }
  std::error_code write(std::span<const std::uint8_t>, hil::Duration) override { return {}; }
  std::uint64_t overrun_count() override { return overruns; }
};
}  // namespace

TEST(SerialStream, ParmrkMarksBecomeErrorsAcrossReadBoundaries) {
  hil::VirtualClock clock;
  auto raw = std::make_unique<ScriptedLine>();
  auto* script = raw.get();
  // "A", literal 0xFF (escaped), parity error on 'x' split across two reads, break, "B".
  script->chunks = {{'A', 0xFF, 0xFF, 0xFF}, {0x00, 'x', 0xFF, 0x00, 0x00, 'B'}};
  LineFormat f = *parse_char_format("8E1");
  SerialStream s(std::move(raw), f, Discipline{.parmrk = true}, clock);
  std::array<std::uint8_t, 16> buf{};
  auto r = s.read_some(buf, 10ms);
  ASSERT_EQ(r.size, 2U);
  EXPECT_EQ(buf[0], 'A');
  EXPECT_EQ(buf[1], 0xFF);
  EXPECT_FALSE(r.error);
  r = s.read_some(buf, 10ms);  // the mark completes in the second chunk: 'x' is dropped
  EXPECT_EQ(r.size, 0U);
  EXPECT_EQ(r.error, LineError::parity);
  r = s.read_some(buf, 10ms);
  EXPECT_EQ(r.size, 0U);
  EXPECT_EQ(r.error, LineError::break_received);
  r = s.read_some(buf, 10ms);
  ASSERT_EQ(r.size, 1U);
  EXPECT_EQ(buf[0], 'B');
  script->overruns = 3;
  script->chunks = {{'C'}};
  r = s.read_some(buf, 10ms);
  EXPECT_EQ(r.size, 1U);
  EXPECT_EQ(r.error, LineError::overrun);
}

TEST(SerialStream, XoffPausesWriterAndStallTimesOutOnVirtualClock) {
  hil::VirtualClock clock;
  auto line = make_memory_line(&clock);
  LineFormat f = *parse_char_format("7E1");
  f.flow = FlowControl::xon_xoff;
  f.xoff = 0x93;  // parity-carrying DC3 as an 8-bit reader sees it
  f.xon = 0x11;
  SerialStream host(std::move(line.a), f, Discipline{.software_parity = true}, clock);
  auto dev = std::move(line.b);
  const std::uint8_t xoff = 0x93;
  ASSERT_FALSE(dev->write(std::span(&xoff, 1), 1s));
  const auto t0 = clock.now();
  auto ec = host.write(bytes("#N0000 NOP\r\n"), 2s);
  EXPECT_EQ(ec, LineError::xoff_stalled);
  EXPECT_GE(clock.now() - t0, 2s);
  EXPECT_EQ(host.written(), 0U) << "nothing may leave while XOFF holds";
  EXPECT_TRUE(host.paused_by_peer());
  // XON releases; flow bytes never appear as data.
  const std::uint8_t xon = 0x11;
  ASSERT_FALSE(dev->write(std::span(&xon, 1), 1s));
  EXPECT_FALSE(host.write(bytes("OK"), 2s));
  std::array<std::uint8_t, 8> buf{};
  auto r = dev->read_some(buf, 10ms);
  EXPECT_EQ(r.size, 2U);
}

TEST(SerialStream, XoffMidWriteStopsWithinAChunk) {
  hil::VirtualClock clock;
  auto line = make_memory_line(&clock);
  LineFormat f;
  f.flow = FlowControl::xon_xoff;
  SerialStream host(std::move(line.a), f, Discipline{.xoff_poll_chunk = 4}, clock);
  auto* dev = line.b.get();
  // The device answers the first chunk with XOFF (as a CLM with a full buffer does).
  *line.a_to_b = [dev, sent = false](std::vector<std::uint8_t>&) mutable {
    if (!sent) {
      const std::uint8_t x = 0x13;
      (void)dev->write(std::span(&x, 1), 1s);
      sent = true;
    }
  };
  auto ec = host.write(bytes("0123456789"), 500ms);
  EXPECT_EQ(ec, LineError::xoff_stalled);
  EXPECT_EQ(host.written(), 4U);
}

TEST(PtyPair, BytesBothWaysAt7E2WithSoftwareParity) {
  hil::SteadyClock clock;
  auto pty = linux_io::PtyEndpoint::create();
  ASSERT_TRUE(pty) << pty.error().message;
  LineFormat f = *parse_char_format("7E2");
  f.baud = 19200;
  SerialStream master(pty->take_master(), f, Discipline{.software_parity = true}, clock);
  auto client = linux_io::open_tty(pty->slave_path(), f, clock);
  ASSERT_TRUE(client) << client.error().message;
  ASSERT_FALSE((*client)->write(bytes("?1X  53 $2C\r\n"), 1s));
  EXPECT_EQ(read_all(master, 13, 2s), "?1X  53 $2C\r\n");
  ASSERT_FALSE(master.write(bytes("Y\r\n"), 1s));
  EXPECT_EQ(read_all(**client, 3, 2s), "Y\r\n");
  // A byte with bad parity from the device side is reported to the client as a parity error.
  const std::uint8_t bad = 0x13;  // DC3 with even parity would be 0x93
  ASSERT_FALSE(master.raw().write(std::span(&bad, 1), 1s));
  std::array<std::uint8_t, 4> buf{};
  auto r = (*client)->read_some(buf, 2s);
  EXPECT_EQ(r.error, LineError::parity);
}

TEST(PtyPair, OpenMissingPortGivesClearError) {
  hil::SteadyClock clock;
  auto r = linux_io::open_tty("/dev/does-not-exist-ttyUSB9", LineFormat{}, clock);
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("/dev/does-not-exist-ttyUSB9"), std::string::npos);
}

TEST(TcpLine, AdapterRoundTrip) {
  hil::SteadyClock clock;
  auto listener = linux_io::TcpListener::create("127.0.0.1", 0);
  ASSERT_TRUE(listener) << listener.error().message;
  const auto port = (*listener)->port();
  std::unique_ptr<RawLine> server;
  std::thread t([&] { server = (*listener)->accept(5s); });
  auto client = linux_io::connect_tcp("127.0.0.1", port, 5s);
  t.join();
  ASSERT_TRUE(client) << client.error().message;
  ASSERT_TRUE(server);
  SerialStream c(std::move(*client), LineFormat{}, Discipline{}, clock);
  SerialStream s(std::move(server), LineFormat{}, Discipline{}, clock);
  ASSERT_FALSE(c.write(bytes(":1\r\n"), 1s));
  EXPECT_EQ(read_all(s, 4, 2s), ":1\r\n");
}
