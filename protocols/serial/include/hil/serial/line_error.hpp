// SPDX-License-Identifier: MIT
#pragma once
// Errors of the serial line itself (below any device protocol): character errors the UART
// reports (parity, framing, overrun, break), flow-control stalls, timeouts and I/O failures.

#include <cstdint>
#include <system_error>

namespace hil::serial {

enum class LineError : std::uint8_t {
  timeout = 1,         ///< nothing (or not enough) arrived before the deadline
  parity = 2,          ///< a character with wrong parity (PARMRK mark on a tty, software parity on pty/TCP)
  framing = 3,         ///< missing stop bit (PARMRK mark 0xFF 0x00 c with c != 0 on a tty)
  overrun = 4,         ///< the UART or the kernel buffer lost characters (TIOCGICOUNT)
  break_received = 5,  ///< line held in spacing state (PARMRK 0xFF 0x00 0x00)
  xoff_stalled = 6,    ///< peer sent XOFF and no XON within the stall timeout
  closed = 7,          ///< peer closed the pty/socket
  dsr_low = 8,         ///< DTR/DSR handshake in use and DSR is not asserted
  cts_stalled = 9,     ///< RTS/CTS in use and the output did not drain within the timeout
  io = 10,             ///< the OS reported an I/O error (see the log for errno)
};

[[nodiscard]] const std::error_category& line_category() noexcept;
[[nodiscard]] inline std::error_code make_error_code(LineError e) noexcept {
  return {static_cast<int>(e), line_category()};
}

}  // namespace hil::serial

template <>
struct std::is_error_code_enum<hil::serial::LineError> : std::true_type {};
