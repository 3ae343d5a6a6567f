// SPDX-License-Identifier: MIT
// The PC <-> ELG data channel (manual 12.5; digest §8.4): the function-module transfer over the
// dual-port RAM by which the PC reads and writes R parameters, machine data, setting data and
// reads actual values, alarms and service data. A request names a 6-bit coding, a two-part
// relative address (decimal "1." = low two digits, "2." = high two digits: MD 2043 is code 10,
// 1. = 43, 2. = 20) and a signed value; a wrong code, a value too high or an impermissible
// dimension gives alarm 3016, an unknown address 3018, and in both cases the transfer is not
// performed but still acknowledged.
//
// The manual gives no byte layout (digest §12.10). [I] hilbridge's frame, 9 bytes, BCD:
//   byte 0   bit 7 = write (1) / read (0), bit 6 = acknowledge (reply), bits 5-0 the coding
//   byte 1   relative address "1." as two BCD digits      byte 2   "2." as two BCD digits
//   byte 3   bit 7 = sign (1 = minus), bits 6-4 = 0, bits 3-0 = decimal places (the dimension)
//   bytes 4-8 ten BCD digits of the value, most significant first (the first must be 0: 9 digits)
// Bit data (codings 28, 29) carry the byte as eight digits 0/1, bit 7 first ("00000001").
#pragma once

#include <array>
#include <cstdint>
#include <expected>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "hil/controllers/elg/alarm.hpp"

namespace hil::controllers::elg {

/// The codings of 12.5 (the values are the manual's).
enum class PcCoding : std::uint8_t {
  r_parameter = 9,    ///< R0..R99, +-99999.999 (variable decimal point)
  word = 10,          ///< MD words 0..4999 (2. = 00..49), service data 8000..8999 (2. = 80..89)
  actual_value = 12,  ///< axes 1..4 (1. = 01..04), read only
  alarms = 27,        ///< the pending ELG alarms (1. = 01..99: the n-th), read only
  md_bits = 28,       ///< MD bits 5000..6999 (2. = 50..69), bytewise
  sd_bits = 29,       ///< SD bits 5000..5999 (2. = 50..59), bytewise
};

/// A signed decimal: value = (negative ? -1 : 1) * digits / 10^decimals.
struct PcValue {
  bool negative = false;
  std::uint8_t decimals = 0;  ///< the dimension identifier: decimal places 0..9
  std::uint64_t digits = 0;   ///< at most 9 decimal digits
  [[nodiscard]] bool operator==(const PcValue&) const = default;
};

struct PcRequest {
  bool write = false;
  std::uint8_t coding = 0;  ///< 6 bits
  std::uint8_t rel1 = 0;    ///< "1.", 0..99
  std::uint8_t rel2 = 0;    ///< "2.", 0..99
  PcValue value;            ///< the datum to write (ignored on a read)
  /// The datum's number: rel2 * 100 + rel1 (MD 2043, R 40, SD 5016, axis 2, alarm slot 3).
  [[nodiscard]] int address() const noexcept { return rel2 * 100 + rel1; }
};

struct PcReply {
  bool acknowledged = true;    ///< always: even a refused transfer is acknowledged (12.5)
  bool performed = false;      ///< the read or write took place
  std::optional<Alarm> alarm;  ///< 3016 / 3018 when not performed
  PcValue value;               ///< the datum read (a write echoes the value stored)
};

inline constexpr std::size_t pc_frame_size = 9;
using PcFrame = std::array<std::uint8_t, pc_frame_size>;

/// Builds the frame of a request (no I/O). Digits above 9 places are cut to the low nine.
PcFrame make_pc_request(const PcRequest& request) noexcept;
/// Reads a request frame: a wrong length, a non-BCD digit, a tenth digit or reserved bits set is
/// 3016 (the manual's "wrong code / impermissible dimension").
std::expected<PcRequest, Alarm> parse_pc_request(std::span<const std::uint8_t> frame) noexcept;
/// The reply frame: the request's address, bit 6 set (acknowledged), the value read.
PcFrame make_pc_reply(const PcRequest& request, const PcReply& reply) noexcept;

/// "-8.18511" style text of a value, and the value of such text (at most 9 digits).
std::string to_string(const PcValue& value);
std::optional<PcValue> parse_pc_value(std::string_view text) noexcept;

}  // namespace hil::controllers::elg
