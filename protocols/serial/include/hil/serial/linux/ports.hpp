// SPDX-License-Identifier: MIT
#pragma once
// Linux backends of the serial byte stream, all on standalone Asio:
//  - open_tty: a tty or pty slave through asio::serial_port, configured with termios/termios2
//    (any baud 110..115200 via BOTHER, CS7/CS8, parity, CSTOPB, CRTSCTS, PARMRK, DTR);
//  - PtyEndpoint: the master side of a fresh pseudo-terminal pair (emulators, tests);
//  - connect_tcp / TcpListener: serial-over-IP adapters (raw TCP, e.g. a Moxa in "TCP server" mode).
// Blocking: every call blocks at most the timeout it is given. Thread: one owner thread.

#include <cstdint>
#include <expected>
#include <memory>
#include <string>
#include <system_error>

#include "hil/serial/byte_stream.hpp"
#include "hil/serial/serial_stream.hpp"

namespace hil::serial::linux_io {

struct OpenError {
  std::error_code code;
  std::string message;  ///< what failed, on which path, and what to try
};

/// Open `path` (e.g. /dev/ttyUSB0 or a /dev/pts/N slave) as a raw serial port with `format`.
/// On a pty (no UART) the discipline uses software parity; on a real tty PARMRK marks.
[[nodiscard]] std::expected<std::unique_ptr<SerialStream>, OpenError> open_tty(const std::string& path,
                                                                               const LineFormat& format,
                                                                               const Clock& clock);

/// Raw (unconfigured) line for an already-open file descriptor; takes ownership of `fd`.
[[nodiscard]] std::unique_ptr<RawLine> adopt_fd(int fd);

/// Master side of a new pseudo-terminal pair. The slave is kept open by this object too, so
/// clients may open and close the slave path any number of times without hanging up the master.
class PtyEndpoint {
 public:
  [[nodiscard]] static std::expected<PtyEndpoint, OpenError> create();
  PtyEndpoint(PtyEndpoint&&) noexcept;
  PtyEndpoint& operator=(PtyEndpoint&&) noexcept;
  ~PtyEndpoint();
  /// Slave path to give to the client ("/dev/pts/7").
  [[nodiscard]] const std::string& slave_path() const noexcept { return slave_path_; }
  /// The master as a raw line (ownership of the master fd moves into it; call once).
  [[nodiscard]] std::unique_ptr<RawLine> take_master();

 private:
  PtyEndpoint() = default;
  int master_fd_ = -1;
  int slave_keepalive_fd_ = -1;
  std::string slave_path_;
};

/// Connect to a serial-over-IP adapter at host:port (raw TCP, the bytes are the line).
[[nodiscard]] std::expected<std::unique_ptr<RawLine>, OpenError> connect_tcp(const std::string& host,
                                                                             std::uint16_t port, Duration timeout);

/// Listen on 127.0.0.1/0.0.0.0:port for one client at a time (emulators behind "TCP").
class TcpListener {
 public:
  [[nodiscard]] static std::expected<std::unique_ptr<TcpListener>, OpenError> create(const std::string& bind_address,
                                                                                     std::uint16_t port);
  virtual ~TcpListener() = default;
  [[nodiscard]] virtual std::uint16_t port() const noexcept = 0;
  /// Wait at most `timeout` for a client; nullptr on timeout or error. A failed accept (out of
  /// file descriptors: the client stays in the backlog and would fail again at once) returns only
  /// when `timeout` has passed, so a caller looping on accept() backs off instead of spinning.
  [[nodiscard]] virtual std::unique_ptr<RawLine> accept(Duration timeout) = 0;
  /// Failed accepts so far (EMFILE, ENFILE, ...), and the last one's error (empty if none).
  [[nodiscard]] virtual std::uint64_t accept_errors() const noexcept = 0;
  [[nodiscard]] virtual std::error_code last_accept_error() const noexcept = 0;
};

}  // namespace hil::serial::linux_io
