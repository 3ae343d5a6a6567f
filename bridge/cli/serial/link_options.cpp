// SPDX-License-Identifier: MIT
#include "link_options.hpp"

#include <csignal>

#include <fmt/format.h>

#include <charconv>

#include "hil/cli/duration_option.hpp"
#include "hil/cli/endpoint_text.hpp"
#include "hil/serial/linux/ports.hpp"
#include "hil/serial/serial_stream.hpp"

namespace hil::cli::serial_cli {

void add_link_options(CLI::App& cmd, LinkOptions& o, bool with_station) {
  cmd.add_option("--port,-p", o.port,
                 "Serial port (/dev/ttyUSB0, a /dev/pts/N printed by `hilbridge emulate`), or tcp://HOST:PORT for a "
                 "serial-over-IP adapter")
      ->required();
  cmd.add_option("--baud,-b", o.baud, "Baud rate, any value 110..115200")->capture_default_str();
  cmd.add_option("--format,-f", o.format, "Character format <data bits 7|8><parity N|E|O><stop bits 1|1.5|2>, e.g. 7E2")
      ->capture_default_str();
  cmd.add_option("--flow", o.flow, "Flow control: none, rtscts or xonxoff")->capture_default_str();
  cmd.add_option("--xon", o.xon, "XON byte as it appears on the wire (e.g. 0x11; 8-bit allowed)")
      ->capture_default_str();
  cmd.add_option("--xoff", o.xoff, "XOFF byte as it appears on the wire (e.g. 0x13, or 0x93 for DC3 with even parity)")
      ->capture_default_str();
  cmd.add_flag("--dtr-dsr", o.dtr_dsr, "Raise DTR and require DSR before sending (devices that use the lines)");
  if (with_station)
    cmd.add_option("--station,-s", o.station, "RS-485 station 1..32 (0 = RS-232 point to point)")
        ->check(CLI::Range(0, 32))
        ->capture_default_str();
  const DurationRange timeout_range{std::chrono::milliseconds(10), std::chrono::minutes(10)};
  add_duration_option(cmd, "--timeout", o.timeout, "Response timeout per telegram, e.g. 2s (default 1s; 10ms .. 10min)",
                      "ms", timeout_range);
  add_duration_alias(cmd, "--timeout-ms", "--timeout", o.timeout, "ms", timeout_range);
  cmd.add_option("--retries", o.retries, "Repeats of a telegram after a checksum error or timeout")
      ->check(CLI::Range(0, 20))
      ->capture_default_str();
}

namespace {
std::expected<std::uint8_t, std::string> parse_byte(const std::string& s, const char* what) {
  try {
    std::size_t used = 0;
    const unsigned long v = std::stoul(s, &used, 0);
    if (used != s.size() || v > 0xFF) throw std::out_of_range(s);
    return static_cast<std::uint8_t>(v);
  } catch (const std::exception&) {
    return std::unexpected(fmt::format("{} '{}' is not a byte: use e.g. 0x11 or 17", what, s));
  }
}
}  // namespace

std::expected<hil::serial::LineFormat, std::string> line_format(const LinkOptions& o) {
  hil::serial::LineFormat base;
  base.baud = o.baud;
  auto flow = hil::serial::parse_flow_control(o.flow);
  if (!flow) return std::unexpected("--flow: " + flow.error().message);
  base.flow = *flow;
  auto xon = parse_byte(o.xon, "--xon");
  if (!xon) return std::unexpected(xon.error());
  auto xoff = parse_byte(o.xoff, "--xoff");
  if (!xoff) return std::unexpected(xoff.error());
  base.xon = *xon;
  base.xoff = *xoff;
  base.use_dtr_dsr = o.dtr_dsr;
  auto f = hil::serial::parse_char_format(o.format, base);
  if (!f) return std::unexpected("--format/--baud: " + f.error().message);
  return *f;
}

std::expected<std::unique_ptr<hil::serial::ByteStream>, std::string> open_link(const LinkOptions& o,
                                                                               const Clock& clock) {
  auto f = line_format(o);
  if (!f) return std::unexpected(f.error());
  // A serial-over-IP adapter: tcp://HOST:PORT (the CLI's TCP spelling, docs/cli.md) or tcp:HOST:PORT
  // (as before, and as `hilbridge emulate --tcp` prints it).
  if (o.port.starts_with("tcp:")) {
    const std::string rest(o.port.starts_with("tcp://") ? strip_tcp_scheme(o.port) : o.port.substr(4));
    const auto colon = rest.rfind(':');
    if (colon == std::string::npos) return std::unexpected(fmt::format("--port {}: expected tcp://HOST:PORT", o.port));
    // The whole text, 1..65535: 99999 or 80x is an error, never a cast to another port.
    const std::string digits = rest.substr(colon + 1);
    unsigned port = 0;
    const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), port);
    if (ec != std::errc{} || end != digits.data() + digits.size() || port < 1 || port > 65535)
      return std::unexpected(fmt::format("--port {}: '{}' is not a TCP port number 1..65535", o.port, digits));
    auto raw = hil::serial::linux_io::connect_tcp(rest.substr(0, colon), static_cast<std::uint16_t>(port),
                                                  std::chrono::seconds(5));
    if (!raw) return std::unexpected(raw.error().message);
    hil::serial::Discipline d;
    d.software_parity = true;  // the adapter forwards the bytes; parity travels in bit 7 for 7-bit formats
    return std::make_unique<hil::serial::SerialStream>(std::move(*raw), *f, d, clock);
  }
  auto s = hil::serial::linux_io::open_tty(o.port, *f, clock);
  if (!s) return std::unexpected(s.error().message);
  return std::unique_ptr<hil::serial::ByteStream>(std::move(*s));
}

std::atomic<bool>& interrupted() {
  static std::atomic<bool> flag{false};
  return flag;
}

namespace {
extern "C" void on_signal(int) {
  interrupted().store(true);
}
}  // namespace

void install_interrupt_handler() {
  struct sigaction sa {};
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  ::sigaction(SIGINT, &sa, nullptr);
  ::sigaction(SIGTERM, &sa, nullptr);
}

}  // namespace hil::cli::serial_cli
