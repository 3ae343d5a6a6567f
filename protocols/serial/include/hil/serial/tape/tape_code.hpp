// SPDX-License-Identifier: MIT
#pragma once
// Punched-tape character codes (notes §4.4):
//  - ISO 840 / DIN 66025: 7-bit ISO characters with even parity in bit 7 (track 8);
//  - EIA RS-244: odd parity on track 5, end of block on track 8 (0x80), EOR 0x0B.
// The EIA table follows the common RS-244-B listing (digits, letters, + - . / , space, BS,
// TAB, DEL, control out/in = tracks 2-4-5 / 2-4-7 as in the Yaskawa table, EOB, EOR). The
// byte-exact standard was not available (notes §4.4 UNVERIFIED): see docs/serial.md.
// Pure functions.

#include <cstdint>
#include <optional>

namespace hil::serial::tape {

enum class Code : std::uint8_t { iso, eia };

/// ISO character (7-bit) to the tape byte with even parity in bit 7: 'T' -> 0xD4, '%' -> 0xA5.
[[nodiscard]] constexpr std::uint8_t make_iso(char c) noexcept {
  const auto v = static_cast<std::uint8_t>(static_cast<std::uint8_t>(c) & 0x7F);
  return static_cast<std::uint8_t>(v | ((__builtin_popcount(v) & 1) ? 0x80 : 0x00));
}
/// Tape byte to ISO character; nullopt if the parity (even over 8 bits) is wrong.
[[nodiscard]] constexpr std::optional<char> parse_iso(std::uint8_t b) noexcept {
  if ((__builtin_popcount(b) & 1) != 0) return std::nullopt;
  return static_cast<char>(b & 0x7F);
}

/// EIA end-of-block (track 8) and end-of-record / rewind stop.
inline constexpr std::uint8_t eia_eob = 0x80;
inline constexpr std::uint8_t eia_eor = 0x0B;

/// ASCII character to EIA byte ('\n' -> EOB, '%' -> EOR, lower case letters as upper case);
/// nullopt for characters EIA does not have ('=', ':', ...).
[[nodiscard]] std::optional<std::uint8_t> make_eia(char c) noexcept;
/// EIA byte to ASCII ('\n' for EOB, '%' for EOR, upper-case letters). nullopt: the parity
/// (odd over 8 bits, EOB excepted) is wrong, or the byte has good parity but no meaning.
struct EiaDecode {
  std::optional<char> c;
  bool parity_ok = false;
};
[[nodiscard]] EiaDecode parse_eia(std::uint8_t b) noexcept;

}  // namespace hil::serial::tape
