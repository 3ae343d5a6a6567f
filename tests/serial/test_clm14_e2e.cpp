// SPDX-License-Identifier: MIT
// End to end: our CLM1.4 client against our emulator. Over a real pty pair (emulator on its own
// thread) at several line formats, with 32 RS-485 stations; and over an in-process line on the
// virtual clock with injected faults: checksum damage (retried), parity errors, a stalled XOFF,
// a missing station (timeout), a device in the wrong mode, and an interrupted send (`hilbridge download`) resumed.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <atomic>
#include <functional>
#include <thread>

#include "hil/mocks/legacy/clm14_line.hpp"
#include "hil/mocks/legacy/endpoint.hpp"
#include "hil/serial/clm14/client.hpp"
#include "hil/serial/clm14/item_devices.hpp"
#include "hil/serial/clm14/serial_error.hpp"
#include "hil/serial/item_transfer.hpp"
#include "hil/serial/linux/ports.hpp"
#include "hil/serial/memory_line.hpp"
#include "hil/serial/serial_stream.hpp"

using namespace hil::serial;
using namespace hil::serial::clm14;
using namespace hil::mocks::legacy;
using namespace std::chrono_literals;

namespace {
std::shared_ptr<const DeviceData> data() {
  static auto d = load_device_data();
  return *d;
}

/// Emulator on a pty served by its own thread; the client opens the slave path.
struct PtyRig {
  hil::SteadyClock clock;
  Clm14Line line;
  std::optional<linux_io::PtyEndpoint> pty;
  std::unique_ptr<SerialStream> device;
  std::unique_ptr<EndpointHost> host;
  std::thread thread;
  std::unique_ptr<SerialStream> client_stream;

  PtyRig(LineFormat f, int stations) : line(data(), stations) {
    auto p = linux_io::PtyEndpoint::create();
    EXPECT_TRUE(p);
    pty.emplace(std::move(*p));
    device = std::make_unique<SerialStream>(pty->take_master(), f, Discipline{.software_parity = true}, clock);
    host = std::make_unique<EndpointHost>(line, *device, clock);
    thread = std::thread([this] { host->run(); });
    auto c = linux_io::open_tty(pty->slave_path(), f, clock);
    EXPECT_TRUE(c) << c.error().message;
    client_stream = std::move(*c);
  }
  ~PtyRig() {
    host->stop();
    thread.join();
  }
  /// The line while its host thread serves it: under the host's lock, as the emulator's console
  /// commands reach it (the stations run their NC cycles on the host thread).
  void on_line(const std::function<void(Clm14Line&)>& fn) {
    host->with_endpoint([&](Endpoint&) { fn(line); });
  }
};

std::vector<Item> program(int lines) {
  std::vector<Item> items;
  for (int i = 0; i < lines; ++i)
    items.push_back(Item{fmt::format("{:04d}", i), i % 2 ? "WAI 00.500" : "AEA Q1.00.3 1"});
  return items;
}
}  // namespace

class PtyFormats : public ::testing::TestWithParam<const char*> {};

TEST_P(PtyFormats, ProgramAndParametersRoundTrip) {
  LineFormat f = *parse_char_format(GetParam());
  f.baud = 115200;
  f.flow = FlowControl::xon_xoff;
  PtyRig rig(f, 0);
  rig.on_line([](Clm14Line& l) { l.set_mode(ClmMode::parameter); });
  Client client(*rig.client_stream, rig.clock, ClientOptions{});
  ProgramDevice prog(client);
  const auto items = program(40);
  auto rep = send_items(prog, items, 0, {}, nullptr);
  ASSERT_TRUE(rep.ok()) << rep.describe();
  auto diffs = verify_items(prog, items, {});
  ASSERT_TRUE(diffs);
  EXPECT_TRUE(diffs->empty());
  ParameterDevice par(client);
  ASSERT_TRUE(par.write_item(Item{"A101", "0020.00000"}));
  EXPECT_EQ(par.read_item("A101").value(), "0020.00000");
  rig.on_line([](Clm14Line& l) { EXPECT_EQ(l.station(0).program_line(39), "WAI 00.500 "); });
}

INSTANTIATE_TEST_SUITE_P(LineFormats, PtyFormats, ::testing::Values("8N1", "7E2", "7O1", "8E1"));

TEST(Clm14EndToEnd, ThirtyTwoRs485StationsOnOnePty) {
  LineFormat f = *parse_char_format("7E1");
  f.baud = 38400;
  PtyRig rig(f, 32);
  for (int st = 1; st <= 32; ++st) {
    Client c(*rig.client_stream, rig.clock, ClientOptions{.station = st});
    ASSERT_TRUE(c.write_program_line(st, fmt::format("WAI {:02d}.000", st))) << "station " << st;
  }
  for (int st = 1; st <= 32; ++st) {
    Client c(*rig.client_stream, rig.clock, ClientOptions{.station = st});
    EXPECT_EQ(c.read_program_line(st).value(), fmt::format("WAI {:02d}.000", st));
    EXPECT_EQ(c.read_program_line(0).value(), "NOP");
    rig.on_line([st](Clm14Line& l) {
      EXPECT_EQ(l.station(static_cast<std::size_t>(st - 1)).program_line(st), fmt::format("WAI {:02d}.000 ", st));
    });
  }
}

namespace {
/// Client and emulator on one thread, virtual clock; the emulator answers inside the write.
struct VirtualRig {
  hil::VirtualClock clock;
  MemoryLinePair mem = make_memory_line(&clock);
  Clm14Line line;
  std::unique_ptr<SerialStream> client_stream;
  RawLine* device_raw;
  std::function<void(std::string&)> damage_reply;  // fault injection on the way back
  bool deaf = false;                               // the station does not answer at all
  std::uint8_t hold_xoff = 0;                      // send this XOFF byte and never XON
  LineFormat format;

  explicit VirtualRig(int stations, LineFormat f = *parse_char_format("7E1")) : line(data(), stations), format(f) {
    client_stream = std::make_unique<SerialStream>(std::move(mem.a), f, Discipline{.software_parity = true}, clock);
    device_raw = mem.b.get();
    *mem.a_to_b = [this](std::vector<std::uint8_t>& bytes) {
      // Decode the software parity like the device's UART would, flag bad characters.
      std::vector<std::uint8_t> clean;
      std::string out;
      for (auto b : bytes) {
        if (!parity7_ok(b, format.parity)) {
          out += line.on_bytes(clean, clock.now());
          clean.clear();
          out += line.on_line_error(LineError::parity, clock.now());
        } else {
          clean.push_back(static_cast<std::uint8_t>(b & 0x7F));
        }
      }
      out += line.on_bytes(clean, clock.now());
      bytes.clear();
      if (hold_xoff != 0) {
        (void)device_raw->write(std::span(&hold_xoff, 1), 1s);
        return;
      }
      if (deaf || out.empty()) return;
      if (damage_reply) damage_reply(out);
      std::vector<std::uint8_t> wire;
      for (char c : out) wire.push_back(with_parity7(static_cast<std::uint8_t>(c), format.parity));
      (void)device_raw->write(wire, 1s);
    };
  }
};
}  // namespace

TEST(Clm14EndToEnd, ChecksumDamageOnTheWayIsRetriedAndSucceeds) {
  VirtualRig rig(0);
  int damaged = 0;
  // Damage the first request on the way to the device: it answers serial error 04, we resend.
  auto original = *rig.mem.a_to_b;
  *rig.mem.a_to_b = [&, original](std::vector<std::uint8_t>& bytes) mutable {
    if (damaged++ == 0) bytes[3] = with_parity7('9', Parity::even);  // "N0005" -> "N9005": checksum no longer fits
    original(bytes);
  };
  Client c(*rig.client_stream, rig.clock, ClientOptions{});
  ASSERT_TRUE(c.write_program_line(5, "WAI 00.500"));
  EXPECT_EQ(c.retries_used(), 1);
  EXPECT_EQ(rig.line.station(0).program_line(5), "WAI 00.500 ");
}

TEST(Clm14EndToEnd, ParityErrorOnTheWayIsReportedByTheDeviceAndRetried) {
  VirtualRig rig(0);
  int n = 0;
  auto original = *rig.mem.a_to_b;
  *rig.mem.a_to_b = [&, original](std::vector<std::uint8_t>& bytes) mutable {
    if (n++ == 0) bytes[4] ^= 0x80;  // wrong parity on one character
    original(bytes);
  };
  Client c(*rig.client_stream, rig.clock, ClientOptions{.retries = 0});
  auto r = c.write_program_line(6, "WAI 00.500");
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().device_error, 2);
  EXPECT_EQ(r.error().code, SerialError::format_error);
  EXPECT_NE(r.error().message.find("RS Format Error"), std::string::npos) << r.error().message;
  EXPECT_EQ(rig.line.station(0).program_line(6), "NOP  ") << "nothing half-written";
}

TEST(Clm14EndToEnd, ParityErrorInTheReplyIsDetectedByTheClient) {
  VirtualRig rig(0);
  rig.damage_reply = [](std::string&) {};
  int n = 0;
  auto* raw = rig.device_raw;
  (void)raw;
  auto original = *rig.mem.b_to_a;
  *rig.mem.b_to_a = [&](std::vector<std::uint8_t>& bytes) {
    if (n++ == 0 && bytes.size() > 3) bytes[2] ^= 0x80;
  };
  Client c(*rig.client_stream, rig.clock, ClientOptions{.retries = 1});
  auto r = c.read_program_line(0);
  ASSERT_TRUE(r) << r.error().message;  // the retry got a clean reply
  EXPECT_EQ(*r, "NOP");
  EXPECT_EQ(c.retries_used(), 1);
}

TEST(Clm14EndToEnd, MissingStationTimesOutOnTheVirtualClock) {
  VirtualRig rig(4);
  Client c(*rig.client_stream, rig.clock, ClientOptions{.station = 7, .response_timeout = 500ms, .retries = 2});
  const auto t0 = rig.clock.now();
  auto r = c.read_program_line(0);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().code, LineError::timeout);
  EXPECT_NE(r.error().message.find("station 7"), std::string::npos) << r.error().message;
  EXPECT_GE(rig.clock.now() - t0, 1500ms);  // 3 attempts x 500 ms, no real waiting
}

TEST(Clm14EndToEnd, StalledXoffStopsTheWriteWithAClearError) {
  LineFormat f = *parse_char_format("7E1");
  f.flow = FlowControl::xon_xoff;
  f.xoff = 0x93;  // DC3 with its even parity bit, as a 7E1 device sends it
  VirtualRig rig(0, f);
  rig.hold_xoff = 0x93;
  Client c(*rig.client_stream, rig.clock, ClientOptions{.write_timeout = 3s});
  ASSERT_TRUE(c.read_program_line(0).has_value() == false);  // first request triggers the XOFF, reply withheld
  auto r = c.write_program_line(1, "WAI 00.500");
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().code, LineError::xoff_stalled);
  EXPECT_NE(r.error().message.find("XOFF"), std::string::npos) << r.error().message;
}

TEST(Clm14EndToEnd, WrongModeGivesInvalidModeAndNothingIsWritten) {
  VirtualRig rig(0);
  Client c(*rig.client_stream, rig.clock, ClientOptions{});
  auto r = c.write_parameter("A101", "0020.00000");
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().device_error, 5);
  EXPECT_NE(r.error().message.find("Invalid Mode"), std::string::npos) << r.error().message;
  EXPECT_EQ(rig.line.station(0).parameter("A101"), "0010.00000");
}

TEST(Clm14EndToEnd, InterruptedSendReportsExactlyAndResumes) {
  VirtualRig rig(0);
  Client c(*rig.client_stream, rig.clock, ClientOptions{.response_timeout = 200ms, .retries = 1});
  ProgramDevice prog(c);
  const auto items = program(100);
  // The line dies after 37 confirmed lines (the emulator stops answering).
  int writes = 0;
  auto original = *rig.mem.a_to_b;
  *rig.mem.a_to_b = [&, original](std::vector<std::uint8_t>& bytes) mutable {
    if (++writes > 37) {
      bytes.clear();
      return;
    }
    original(bytes);
  };
  std::size_t journal_next = 0;
  auto rep = send_items(prog, items, 0, {}, nullptr, [&](std::size_t i) { journal_next = i + 1; });
  ASSERT_FALSE(rep.ok());
  EXPECT_EQ(rep.confirmed, 37U);
  EXPECT_EQ(rep.in_doubt, "0037");
  EXPECT_EQ(journal_next, 37U);
  EXPECT_NE(rep.describe().find("confirmed 0000..0036 (37 items); 0037 was sent but not confirmed"), std::string::npos)
      << rep.describe();
  EXPECT_NE(rep.describe().find("62 item(s) not sent"), std::string::npos) << rep.describe();
  // The line is back: resume from the journal.
  *rig.mem.a_to_b = original;
  auto rest = send_items(prog, items, journal_next, {}, nullptr);
  ASSERT_TRUE(rest.ok()) << rest.describe();
  EXPECT_EQ(rest.confirmed, 63U);
  auto diffs = verify_items(prog, items, {});
  ASSERT_TRUE(diffs);
  EXPECT_TRUE(diffs->empty());
}

TEST(Clm14EndToEnd, VerifyListsEveryDifferingLine) {
  VirtualRig rig(0);
  Client c(*rig.client_stream, rig.clock, ClientOptions{});
  ProgramDevice prog(c);
  auto items = program(10);
  ASSERT_TRUE(send_items(prog, items, 0, {}, nullptr).ok());
  items[3].text = "JMP 0000";
  items[7].text = "JMP 0001";
  auto diffs = verify_items(prog, items, {});
  ASSERT_TRUE(diffs);
  ASSERT_EQ(diffs->size(), 2U);
  EXPECT_EQ((*diffs)[0].key, "0003");
  EXPECT_EQ((*diffs)[1].actual, "WAI 00.500");
}
