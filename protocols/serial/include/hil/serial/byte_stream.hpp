// SPDX-License-Identifier: MIT
#pragma once
// The serial byte stream: what every device protocol (CLM1.4 telegrams, tape text, 3964R)
// reads and writes. Backends: a tty or pty slave (Asio serial_port), a pty master, a TCP
// serial-over-IP adapter, and in-memory lines for tests.
//
// Threading: one owner thread calls read/write; the calls block for at most the given time.
// The time a call waits is measured by the backend; protocol deadlines are computed by the
// caller from the injected hil::Clock and passed in as the remaining duration.

#include <cstddef>
#include <cstdint>
#include <span>
#include <system_error>

#include "hil/core/clock.hpp"
#include "hil/serial/line_error.hpp"
#include "hil/serial/line_format.hpp"

namespace hil::serial {

struct ReadResult {
  std::size_t size = 0;   ///< valid bytes placed at the start of the buffer
  std::error_code error;  ///< empty, or why the read stopped after `size` bytes (LineError or OS)
};

/// Lowest layer: bytes as the OS or the test line delivers them (8 bit, PARMRK marks included
/// on a tty, parity bits included on a pty with software parity, XON/XOFF not filtered).
class RawLine {
 public:
  virtual ~RawLine() = default;
  /// Wait at most `timeout` (0 = poll) for at least one byte. Returns size 0 + timeout when none.
  virtual ReadResult read_some(std::span<std::uint8_t> buf, Duration timeout) = 0;
  /// Write all of `data` within `timeout`; cts_stalled/timeout if the OS did not take it.
  virtual std::error_code write(std::span<const std::uint8_t> data, Duration timeout) = 0;
  /// Line error counters from the driver (tty: TIOCGICOUNT overrun); 0 where unsupported.
  virtual std::uint64_t overrun_count() { return 0; }
  /// DSR state where the backend has modem lines; true otherwise.
  virtual bool dsr() { return true; }
  /// Hold the line in the spacing state for `d` (tty only; others ignore it).
  virtual void send_break(Duration) {}
};

/// Character stream for device protocols, after line discipline (parity, PARMRK, XON/XOFF).
class ByteStream {
 public:
  virtual ~ByteStream() = default;
  /// Read at least one byte, waiting at most `timeout`. Line errors (parity/framing/overrun)
  /// end the read: `size` bytes before the bad character are valid, the bad character is
  /// dropped, and `error` says which error. XON/XOFF bytes never appear in the data.
  virtual ReadResult read_some(std::span<std::uint8_t> buf, Duration timeout) = 0;
  /// Write all bytes, honouring flow control; xoff_stalled if the peer holds XOFF longer than
  /// `timeout`. Bytes already sent before an error are reported through `written()`.
  virtual std::error_code write(std::span<const std::uint8_t> data, Duration timeout) = 0;
  /// Send one flow-control byte (XON/XOFF) immediately, outside any pause.
  virtual std::error_code send_flow(bool xon) = 0;
  [[nodiscard]] virtual const LineFormat& format() const noexcept = 0;
  /// Total payload bytes written / read since construction (for progress and partial-write reports).
  [[nodiscard]] virtual std::uint64_t written() const noexcept = 0;
  [[nodiscard]] virtual std::uint64_t received() const noexcept = 0;
};

}  // namespace hil::serial
