// SPDX-License-Identifier: MIT
#pragma once
// Line discipline over a RawLine: software parity (pty/TCP carry 7 data bits + parity in one
// byte), PARMRK error marks (tty), XON/XOFF in both directions with configurable bytes, and
// byte counters. The same class serves the client side and the emulators.

#include <cstdint>
#include <deque>
#include <memory>
#include <system_error>

#include "hil/serial/byte_stream.hpp"

namespace hil::serial {

struct Discipline {
  /// Compute/check the parity bit in software (bit 7), for 7-bit formats on a pty or TCP
  /// line where no UART does it. Ignored for 8-bit formats.
  bool software_parity = false;
  /// The raw bytes carry termios PARMRK marks (0xFF 0x00 c, 0xFF 0xFF) from a tty.
  bool parmrk = false;
  /// Bytes written between two looks for an incoming XOFF (a UART stops within a few chars).
  std::size_t xoff_poll_chunk = 8;
};

class SerialStream final : public ByteStream {
 public:
  /// `raw` is owned. `clock` measures the XOFF stall and the remaining wait of read/write.
  SerialStream(std::unique_ptr<RawLine> raw, LineFormat format, Discipline discipline, const Clock& clock);

  ReadResult read_some(std::span<std::uint8_t> buf, Duration timeout) override;
  std::error_code write(std::span<const std::uint8_t> data, Duration timeout) override;
  std::error_code send_flow(bool xon) override;
  [[nodiscard]] const LineFormat& format() const noexcept override { return format_; }
  [[nodiscard]] std::uint64_t written() const noexcept override { return written_; }
  [[nodiscard]] std::uint64_t received() const noexcept override { return received_; }

  /// True while the peer's last flow byte was XOFF.
  [[nodiscard]] bool paused_by_peer() const noexcept { return paused_; }
  [[nodiscard]] RawLine& raw() noexcept { return *raw_; }

 private:
  // Pull raw bytes (waiting at most `timeout`) through the discipline into pending_.
  std::error_code fill(Duration timeout);
  void decode(std::span<const std::uint8_t> raw);
  void push_error(LineError e);
  std::uint8_t encode(std::uint8_t c) const noexcept;

  std::unique_ptr<RawLine> raw_;
  LineFormat format_;
  Discipline discipline_;
  const Clock& clock_;
  // Decoded bytes; an entry > 0xFF is a line error marker (0x100 + LineError).
  std::deque<std::uint16_t> pending_;
  int parmrk_state_ = 0;  // 0 = normal, 1 = after 0xFF, 2 = after 0xFF 0x00
  bool paused_ = false;
  std::uint64_t written_ = 0;
  std::uint64_t received_ = 0;
  std::uint64_t overruns_seen_ = 0;
};

}  // namespace hil::serial
