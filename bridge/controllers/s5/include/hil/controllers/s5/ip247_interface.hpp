// SPDX-License-Identifier: MIT
#pragma once
// The PLC side of an IP247 axis: the parameter encodings of FB164 (manual §6.2.7.2, digest
// ip247.md §5.4: binary two's complement or BCD with a sign nibble, speeds BCD with a x10 byte)
// and the axis interface DB through which a PLC (or a scenario, or a PG on the RK512 line)
// commands an axis and reads its status. Our DB layout follows the FB164 axis DB (20 words):
//   DW0  DL = BA, DR = byte parameter          DW1  word parameter (speed)
//   DW2/3 double-word parameter (target/distance/offset)
//   DW4  command bits, acted on when set: bit0 Start, bit1 Stop, bit2 Vorwärts, bit3 Rückwärts,
//        bit4 Übernahme (the module clears DW4 when it has taken the job: the handshake)
//   DW5/6 actual value   DW7/8 0   DW9/10 remaining distance
//   DW11 DL = BA, DR = M function   DW12 DL = attribute byte, DR = error number
//   DW13 flags: bit0 = waits for takeover, bit1 = interrupted (waits for continuation)
// Values in binary, or BCD when the MD say "AG values BCD-coded". Pure.

#include <cstdint>
#include <expected>
#include <optional>
#include <vector>

#include "hil/controllers/s5/ip247_axis.hpp"
#include "hil/stepdir/ip247_error.hpp"

namespace hil::controllers::s5 {

inline constexpr std::size_t ip247_axis_db_words = 20;

/// 32-bit double word: binary two's complement, or BCD (sign nibble 0000/1111, 7 decades).
/// BCD out of +-9 999 999 cannot be encoded (std::nullopt).
[[nodiscard]] std::optional<std::uint32_t> encode_ip247_dd(std::int64_t v, bool bcd) noexcept;
/// Error 66 (path not BCD) for a non-BCD nibble or sign.
[[nodiscard]] std::expected<std::int64_t, stepdir::Ip247Error> decode_ip247_dd(std::uint32_t w, bool bcd) noexcept;

struct Ip247SpeedWord {
  std::uint16_t word = 0;
  std::uint8_t byte = 0;  ///< BCD: 1 = word x 10
  friend bool operator==(const Ip247SpeedWord&, const Ip247SpeedWord&) = default;
};
[[nodiscard]] std::optional<Ip247SpeedWord> encode_ip247_speed(std::int32_t v, bool bcd) noexcept;
/// Error 67 (speed not BCD).
[[nodiscard]] std::expected<std::int32_t, stepdir::Ip247Error> decode_ip247_speed(Ip247SpeedWord s, bool bcd) noexcept;

/// The job in an axis DB image whose DW4 has a command bit set, or nothing. Parameter decoding
/// errors (66/67) are returned as the error.
[[nodiscard]] std::optional<std::expected<Ip247Job, stepdir::Ip247Error>> take_ip247_job(
    const std::vector<std::uint16_t>& db, bool bcd);
/// Writes the status words (DW5..DW13) of `axis` into the image and clears DW4.
void write_ip247_status(std::vector<std::uint16_t>& db, const Ip247Axis& axis, bool bcd);

}  // namespace hil::controllers::s5
