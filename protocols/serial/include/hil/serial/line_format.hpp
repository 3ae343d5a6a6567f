// SPDX-License-Identifier: MIT
#pragma once
// Character format of an asynchronous serial line (V.24 / RS-232, RS-485, 20 mA current loop):
// baud rate, data bits, parity, stop bits, flow control and the XON/XOFF bytes.
// Pure value type; parse_ helpers take the notation technicians write ("9600 7E2").

#include <chrono>
#include <cstdint>
#include <expected>
#include <string>
#include <string_view>

namespace hil::serial {

enum class Parity : std::uint8_t { none, even, odd };
enum class StopBits : std::uint8_t { one, one_and_half, two };
enum class FlowControl : std::uint8_t { none, rts_cts, xon_xoff };

/// A line format. Defaults: 9600 8N1, no flow control, XON 0x11 / XOFF 0x13.
struct LineFormat {
  std::uint32_t baud = 9600;   ///< bit/s, 110..115200 (any integer, not only the standard rates)
  std::uint8_t data_bits = 8;  ///< 7 or 8
  Parity parity = Parity::none;
  StopBits stop_bits = StopBits::one;
  FlowControl flow = FlowControl::none;
  /// XON/XOFF bytes as they appear on the wire. With 7 data bits and the port read as 8 bit
  /// (pty/TCP, software parity) they may carry the parity bit, e.g. 0x93 for DC3 with even parity.
  std::uint8_t xon = 0x11;
  std::uint8_t xoff = 0x13;
  bool use_dtr_dsr = false;  ///< raise DTR while open and require DSR before sending

  friend bool operator==(const LineFormat&, const LineFormat&) = default;

  /// Bits per character on the wire, times 2 (1.5 stop bits make it fractional): start + data +
  /// parity + stop. 7E2 -> 2*11 = 22.
  [[nodiscard]] constexpr std::uint32_t half_bits_per_char() const noexcept {
    const std::uint32_t stop = stop_bits == StopBits::one ? 2U : stop_bits == StopBits::two ? 4U : 3U;
    return 2U * (1U + data_bits + (parity == Parity::none ? 0U : 1U)) + stop;
  }
  /// Physical time to transmit `chars` characters back to back at this baud rate.
  [[nodiscard]] constexpr std::chrono::nanoseconds line_time(std::uint64_t chars) const noexcept {
    // half-bits * 1e9 / (2 * baud), in 128-bit-safe order for realistic sizes.
    return std::chrono::nanoseconds{static_cast<std::int64_t>(chars * half_bits_per_char() * 500'000'000ULL / baud)};
  }
  /// "9600 7E2 xon/xoff"
  [[nodiscard]] std::string describe() const;
};

/// Error text for a format the caller gave (what was wrong and what is allowed).
struct FormatError {
  std::string message;
};

/// Parse a character-format shorthand "7E2", "8N1", "7O1.5" into `base` (baud and flow kept).
[[nodiscard]] std::expected<LineFormat, FormatError> parse_char_format(std::string_view text, LineFormat base = {});
/// Check a complete format: baud 110..115200, data 7/8, 7 data bits without parity is allowed
/// (then the 8th bit is ignored), XON != XOFF when XON/XOFF flow control is used.
[[nodiscard]] std::expected<LineFormat, FormatError> validate(const LineFormat& f);
/// "none", "rtscts", "xonxoff"
[[nodiscard]] std::expected<FlowControl, FormatError> parse_flow_control(std::string_view text);

/// Even/odd parity bit for the low 7 bits of `c` (returned in bit 7), for software parity.
[[nodiscard]] constexpr std::uint8_t with_parity7(std::uint8_t c, Parity p) noexcept {
  c &= 0x7F;
  if (p == Parity::none) return c;
  const bool odd_ones = (__builtin_popcount(c) & 1) != 0;
  const bool set = p == Parity::even ? odd_ones : !odd_ones;
  return static_cast<std::uint8_t>(c | (set ? 0x80 : 0x00));
}
/// True when the 8-bit `c` has the right parity for 7 data bits plus parity in bit 7.
[[nodiscard]] constexpr bool parity7_ok(std::uint8_t c, Parity p) noexcept {
  return p == Parity::none || with_parity7(c, p) == c;
}

}  // namespace hil::serial
