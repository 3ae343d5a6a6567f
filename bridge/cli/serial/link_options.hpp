// SPDX-License-Identifier: MIT
#pragma once
// Options shared by the serial commands (port, line format, station, timeouts) and opening
// the line they describe.

#include <CLI/CLI.hpp>

#include <atomic>
#include <expected>
#include <memory>
#include <string>

#include "hil/core/clock.hpp"
#include "hil/serial/byte_stream.hpp"
#include "hil/serial/line_format.hpp"

namespace hil::cli::serial_cli {

struct LinkOptions {
  std::string port;  ///< /dev/ttyUSB0, /dev/pts/N, or tcp:HOST:PORT
  std::uint32_t baud = 9600;
  std::string format = "8N1";
  std::string flow = "none";
  std::string xon = "0x11";
  std::string xoff = "0x13";
  bool dtr_dsr = false;
  int station = 0;
  Duration timeout = std::chrono::milliseconds(1000);  ///< per telegram
  int retries = 2;
};

/// Adds --port, --baud, --format, --flow, --xon, --xoff, --dtr-dsr, --station, --timeout (alias --timeout-ms),
/// --retries.
void add_link_options(CLI::App& cmd, LinkOptions& o, bool with_station);
/// The LineFormat the options describe, or a message saying which option is wrong.
[[nodiscard]] std::expected<hil::serial::LineFormat, std::string> line_format(const LinkOptions& o);
/// Open the line (tty/pty via termios, or TCP for tcp:HOST:PORT).
[[nodiscard]] std::expected<std::unique_ptr<hil::serial::ByteStream>, std::string> open_link(const LinkOptions& o,
                                                                                             const Clock& clock);
/// Set by SIGINT/SIGTERM while a transfer runs (so it can stop cleanly and report).
std::atomic<bool>& interrupted();
void install_interrupt_handler();

}  // namespace hil::cli::serial_cli
